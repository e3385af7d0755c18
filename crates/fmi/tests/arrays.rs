//! The core's one-declaration arrays (`core::arrays`): strided value references,
//! Boolean arrays, derivative arrays, and the table check on them. The expected value
//! references follow from the declaration (first + i * stride), the expected names
//! from the FMI 2.0 convention `base[i]` / `der(base[i])`.

use robofmu_fmi::core::Variable;
use robofmu_fmi::core::arrays::{BooleanArray, RealArray};
use robofmu_fmi::core::check::check_table;
use robofmu_fmi::core::variables::{Kind, find};

/// Two axes' worth of boundary values interleaved by axis as the Planner declares
/// them: q0[a] at 10 a, qf[a] at 10 a + 1.
#[derive(Clone, Default)]
struct Axes {
    q0: [f64; 3],
    qf: [f64; 3],
}

fn strided(
    first_vr: u32,
    base: &'static str,
    field: fn(&mut Axes) -> &mut [f64; 3],
) -> Vec<Variable<Axes>> {
    RealArray::new(first_vr, base, 3, "boundary value", move |m: &Axes, i| {
        field(&mut m.clone())[i]
    })
    .stride(10)
    .set(move |m, i, v| {
        field(m)[i] = v;
        Ok(())
    })
    .each(|v, _| v.state().start_real(0.0))
    .variables()
}

fn interleaved() -> Vec<Variable<Axes>> {
    let mut table = strided(10, "q0", |m| &mut m.q0);
    table.extend(strided(11, "qf", |m| &mut m.qf));
    table.sort_by_key(|v| v.value_reference);
    table
}

#[test]
fn a_strided_array_puts_element_i_at_first_plus_i_times_stride() {
    let table = strided(10, "q0", |m| &mut m.q0);
    let found: Vec<(String, u32)> = table
        .iter()
        .map(|v| (v.name().into_owned(), v.value_reference))
        .collect();
    let found: Vec<(&str, u32)> = found.iter().map(|(n, vr)| (n.as_str(), *vr)).collect();
    assert_eq!(found, [("q0[1]", 10), ("q0[2]", 20), ("q0[3]", 30)]);
    let element = table[2].array.expect("an array element");
    assert_eq!((element.index, element.length, element.stride), (2, 3, 10));
    // From element 3 (vr 30) back to element 1 and on to element 2.
    assert_eq!(element.value_reference(30, 0), 10);
    assert_eq!(element.value_reference(30, 1), 20);
}

#[test]
fn interleaved_strided_arrays_pass_the_table_check_and_read_and_write_their_field() {
    let table = interleaved();
    assert_eq!(check_table(&table), Ok(()));
    let vrs: Vec<u32> = table.iter().map(|v| v.value_reference).collect();
    assert_eq!(vrs, [10, 11, 20, 21, 30, 31]);
    let mut model = Axes {
        q0: [1.0, 2.0, 3.0],
        qf: [4.0, 5.0, 6.0],
    };
    // qf[2] is at 11 + 10: it reads and writes qf[1] (0-based) and nothing else.
    let Some(Kind::Real {
        get,
        set: Some(set),
        ..
    }) = find(&table, 21).map(|v| &v.kind)
    else {
        panic!("qf[2] is a settable Real at value reference 21");
    };
    assert_eq!(get.call(&model), 5.0);
    set.call(&mut model, -7.5).unwrap();
    assert_eq!(model.qf, [4.0, -7.5, 6.0]);
    assert_eq!(model.q0, [1.0, 2.0, 3.0]);
}

#[test]
fn overlapping_value_references_are_rejected() {
    // Stride 1 from 10 puts q0[2] on 11, where qf[1] (stride 10) already is.
    let mut table = RealArray::new(10, "q0", 3, "b", |m: &Axes, i| m.q0[i])
        .set(|m, i, v| {
            m.q0[i] = v;
            Ok(())
        })
        .each(|v, _| v.state().start_real(0.0))
        .variables();
    table.extend(strided(11, "qf", |m| &mut m.qf));
    table.sort_by_key(|v| v.value_reference);
    let message = check_table(&table).unwrap_err();
    assert!(message.contains("not strictly increasing"), "{message}");
}

#[test]
fn stride_zero_is_rejected() {
    let table = RealArray::new(10, "q0", 3, "b", |m: &Axes, i| m.q0[i])
        .stride(0)
        .each(|v, _| v.output())
        .variables();
    assert!(check_table(&table).is_err());
}

#[test]
fn an_element_moved_off_its_stride_is_rejected() {
    let mut table = interleaved();
    // qf[3] declared at 31 moved to 32: its array no longer finds it at 11 + 2 * 10.
    table[5].value_reference = 32;
    let message = check_table(&table).unwrap_err();
    assert!(
        message.contains("is not at value reference 31"),
        "{message}"
    );
}

#[test]
fn boolean_and_derivative_arrays_are_named_like_hand_declared_scalars() {
    #[derive(Clone, Default)]
    struct Switches {
        on: [bool; 2],
        x: [f64; 2],
    }
    let mut table = BooleanArray::new(1, "on", 2, "switch", |m: &Switches, i| m.on[i])
        .label("Channel")
        .set(|m, i, v| {
            m.on[i] = v;
            Ok(())
        })
        .each(|v, _| v.input().start_boolean(false))
        .variables();
    table.extend(
        RealArray::new(3, "x", 2, "state", |m: &Switches, i| m.x[i])
            .set(|m, i, v| {
                m.x[i] = v;
                Ok(())
            })
            .each(|v, _| v.state().start_real(1.0))
            .variables(),
    );
    table.extend(RealArray::derivatives(5, "x", 2, "rate", |m: &Switches, i| -m.x[i]).variables());
    assert_eq!(check_table(&table), Ok(()));
    let shown: Vec<(String, String)> = table
        .iter()
        .map(|v| (v.name().to_string(), v.description().to_string()))
        .collect();
    assert_eq!(shown[0], ("on[1]".into(), "Channel 1: switch".into()));
    assert_eq!(shown[1], ("on[2]".into(), "Channel 2: switch".into()));
    assert_eq!(shown[5], ("der(x[2])".into(), "rate".into()));
    assert_eq!(table[5].state_name().as_deref(), Some("x[2]"));
    let Kind::Boolean {
        get,
        set: Some(set),
        ..
    } = &table[1].kind
    else {
        panic!("on[2] is a settable Boolean");
    };
    let mut model = Switches::default();
    set.call(&mut model, true).unwrap();
    assert_eq!((model.on, get.call(&model)), ([false, true], true));
}
