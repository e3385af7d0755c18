//! The declarative table (`core::declare`): the value-reference scheme, the FMI 2.0
//! scalars an array declaration flattens to, and the hooks routed by element. The
//! expected value references follow from the scheme in the module documentation
//! (pinned: vr + i * stride; unpinned: one after the largest before), the expected
//! names from the FMI 2.0 convention `base[i]` / `der(state[i])`.

use robofmu_fmi::core::declare::{Declaration, unique_value_references, value_references};
use robofmu_fmi::core::flatten::flatten;
use robofmu_fmi::core::variables::Kind;
use robofmu_fmi::core::variables::check_table;
use robofmu_fmi::core::variables::{Causality, VariableType};
use robofmu_fmi::core::{OutputDerivativeError, Var, Variability};
use robofmu_fmi::fmi3::table::{Source, Table3, Variable3};

#[derive(Clone, Default)]
struct Axes {
    x: [f64; 2],
    k: i32,
    ramp: [f64; 2],
}

type Decl = Declaration<Axes>;

const K: Decl = Decl::integer("k", "a gain", |m, _| m.k)
    .set_integer(|m, _, v| {
        m.k = v;
        Ok(())
    })
    .parameter(Variability::Fixed)
    .start_integer(&[4]);
const X: Decl = Decl::real("x", "position", |m, i| m.x[i])
    .array(2)
    .at(10)
    .stride(5)
    .label("Axis")
    .set_real(|m, i, v| {
        m.x[i] = v;
        Ok(())
    })
    .state()
    .start_real(&[1.5, -2.5]);
/// y[i] depends on x[i] alone; at initialization on time, k, all of x and x[2].
static Y_DEPENDS: [Var; 1] = [X.same()];
static Y_KNOWNS: [Var; 4] = [Var::Time, K.var(), X.var(), X.item(1)];

static TABLE: &[Decl] = &[
    K,
    X,
    Decl::real("der(x)", "velocity", |m, i| 3.0 * m.x[i])
        .array(2)
        .derivative_of(X.name),
    Decl::real("u", "input", |m, i| m.x[i])
        .array(2)
        .set_real(|_, _, _| Ok(()))
        .input()
        .start_real(&[0.0])
        .input_derivative(|m, i, order| (order == 1).then(|| &mut m.ramp[i])),
    Decl::real("y", "output", |m, i| m.x[i] * m.x[i])
        .array(2)
        .output()
        .depends_on(&Y_DEPENDS)
        .initial_depends_on(&Y_KNOWNS)
        .output_derivative(1, |m, i, order| match order {
            1 => Ok(2.0 * m.x[i]),
            _ => Err(OutputDerivativeError::NotProvided(
                "order 1 only".to_string(),
            )),
        }),
];

#[test]
fn value_references_are_pinned_or_follow_the_largest_before() {
    // k: first unpinned -> 1; x pinned at 10, stride 5 -> 10, 15; der(x): 16, 17;
    // u: 18, 19; y: 20, 21.
    assert_eq!(value_references(TABLE), [1, 10, 16, 18, 20]);
    let vrs: Vec<u32> = flatten(TABLE).iter().map(|v| v.value_reference).collect();
    assert_eq!(vrs, [1, 10, 15, 16, 17, 18, 19, 20, 21]);
}

// The table's value references are distinct: checked while compiling this test.
const _: () = unique_value_references(TABLE);

/// Whether `unique_value_references` refuses the table, and the declaration it names.
fn refused(table: &[Decl]) -> Option<String> {
    let run = std::panic::catch_unwind(|| unique_value_references(table));
    run.err()
        .map(|e| e.downcast_ref::<String>().cloned().unwrap_or_default())
}

#[test]
fn a_value_reference_taken_twice_is_refused_naming_the_later_declaration() {
    let a = Decl::real("a", "", |m, i| m.x[i]).array(2).at(10).stride(5);
    let b = |vr| Decl::real("b", "", |m, _| m.x[0]).at(vr);
    // a holds 10 and 15 (vr + i * stride); 12 lies between them, 15 is a's second.
    assert_eq!(refused(&[a, b(12)]), None);
    assert_eq!(refused(&[a, b(15)]).as_deref(), Some("b"));
    // Unpinned after a: 16 (one after the largest before), so pinning c at 16 collides.
    let (c, d) = (b(16), Decl::real("d", "", |m, _| m.x[1]));
    assert_eq!(refused(&[a, d, c]).as_deref(), Some("b"));
    assert_eq!(refused(&[a, c, d]), None); // d then takes 17
    // The scheme's references of the accepted table.
    assert_eq!(value_references(&[a, c, d]), [10, 16, 17]);
}

#[test]
fn arrays_flatten_to_fmi2_scalars_with_labels_and_per_element_starts() {
    let table = flatten(TABLE);
    // Named from the declaration when asked (nothing formatted at flattening).
    let names: Vec<String> = table.iter().map(|v| v.name().into_owned()).collect();
    assert_eq!(
        names,
        [
            "k",
            "x[1]",
            "x[2]",
            "der(x[1])",
            "der(x[2])",
            "u[1]",
            "u[2]",
            "y[1]",
            "y[2]"
        ]
    );
    // The allocation-free name of messages writes the same text (second formulation).
    let shown: Vec<String> = table.iter().map(|v| v.shown_name().to_string()).collect();
    assert_eq!(shown, names);
    assert_eq!(table[2].description(), "Axis 2: position");
    assert_eq!(table[3].description(), "velocity");
    let start = |i: usize| match table[i].kind {
        Kind::Real { start, .. } => start,
        _ => None,
    };
    assert_eq!(
        (start(1), start(2), start(5), start(6)),
        (Some(1.5), Some(-2.5), Some(0.0), Some(0.0))
    );
    assert_eq!(table[4].state_name().as_deref(), Some("x[2]"));
    assert_eq!(table[4].state_key(), Some(("x", Some(1))));
    assert_eq!(table[2].key(), ("x", Some(1)));
    // y[i] = x[i]^2 depends on x[i] alone (the per-element hook, called with the index).
    let names = |list: &[&str]| Some(list.iter().map(|s| s.to_string()).collect::<Vec<_>>());
    assert_eq!(table[7].dependencies, names(&["x[1]"]));
    assert_eq!(table[8].dependencies, names(&["x[2]"]));
    // The handles as FMI 2.0 names: time, a scalar, a whole array, one element.
    let knowns = ["time", "k", "x[1]", "x[2]", "x[2]"];
    assert_eq!(table[8].initial_dependencies, names(&knowns));
    // The count of continuous states follows from the derivative declarations.
    assert_eq!(robofmu_fmi::core::declare::continuous_states(TABLE), 2);
    let element = table[4].element();
    assert_eq!((element.name, element.index), ("der(x)", 1));
    let mut sorted = table;
    sorted.sort_by_key(|v| v.value_reference);
    check_table(&sorted).expect("a legal table");
}

#[test]
fn accessors_and_hooks_reach_their_element() {
    let table = flatten(TABLE);
    let mut m = Axes::default();
    let (Kind::Real { set: Some(set), .. }, Kind::Real { get, .. }) =
        (&table[2].kind, &table[4].kind)
    else {
        panic!("x[2] settable, der(x[2]) readable")
    };
    set.call(&mut m, 2.0).unwrap();
    assert_eq!(m.x, [0.0, 2.0]);
    assert_eq!(get.call(&mut m), 6.0); // d/dt x = 3 x
    let (hook, i) = (
        table[8].output_hook().expect("y has output derivatives"),
        table[8].index,
    );
    assert_eq!(hook(&m, i, 1), Ok(4.0)); // d(x^2)/dx = 2 x at x = 2
    let slot = table[6]
        .input_hook()
        .expect("u has an input-derivative slot");
    let i = table[6].index;
    *slot(&mut m, i, 1).expect("order 1 kept") = 0.5;
    assert_eq!(m.ramp, [0.0, 0.5]);
    assert!(slot(&mut m, i, 2).is_none());
}

/// An FMI 3.0 array of 3 elements at value references 10, 20, 30 (first 10, stride 10).
fn strided_array(value_reference: u32) -> Variable3 {
    Variable3 {
        value_reference,
        name: "q".into(),
        variable_type: VariableType::Real,
        causality: Causality::Output,
        variability: Variability::Continuous,
        initial: None,
        dimension: Some(3),
        source: Source::Elements {
            first: value_reference,
            stride: 10,
            declaration: 0,
            element: 0,
        },
        derivative_of: None,
        sized_by: None,
    }
}

#[test]
fn fmi3_elements_are_index_arithmetic_and_lookups_find_every_variable() {
    // Expected: element k at first + k * stride (the scheme of core/declare.rs).
    let q = strided_array(10);
    assert_eq!(q.elements().collect::<Vec<_>>(), [10, 20, 30]);
    assert_eq!(q.elements().len(), 3);
    let time = Variable3 {
        source: Source::Time,
        dimension: None,
        ..strided_array(0)
    };
    assert!(time.elements().is_empty());
    // Description order not by value reference (40 before 11): the lookup still finds
    // each, and nothing else.
    let table = Table3::new(vec![time, strided_array(40), strided_array(11)]);
    for vr in [0, 40, 11] {
        assert_eq!(table.find(vr).map(|v| v.value_reference), Some(vr));
    }
    assert!(table.find(20).is_none());
    // In value-reference order (searched directly).
    let sorted = Table3::new(vec![strided_array(11), strided_array(40)]);
    assert_eq!(sorted.find(40).map(|v| v.value_reference), Some(40));
    assert!(sorted.find(12).is_none());
}

/// A model whose kept variables are declared by place; `changes` counts the writes
/// `after_set` saw, `sum` is what it keeps up to date.
#[derive(Clone, Default)]
struct Kept {
    gain: [f64; 2],
    on: bool,
    order: i32,
    sum: f64,
    changes: u32,
}

fn resum(m: &mut Kept, _: usize) {
    m.sum = m.gain[0] + m.gain[1];
    m.changes += 1;
}

type KeptDecl = Declaration<Kept>;

static KEPT: &[KeptDecl] = &[
    KeptDecl::real_in("gain", |m, i| &mut m.gain[i])
        .describe("two gains")
        .array(2)
        .parameter(Variability::Tunable)
        .start_real(&[1.0, 2.0])
        .after_set(resum),
    KeptDecl::boolean_in("on", |m, _| &mut m.on)
        .parameter(Variability::Fixed)
        .start_boolean(&[true]),
    // A writer of its own checks the value; the place still serves reading.
    KeptDecl::integer_in("order", |m, _| &mut m.order)
        .set_integer(|m, _, v| {
            if v % 2 == 0 {
                return Err("the order is odd".to_string());
            }
            m.order = v;
            Ok(())
        })
        .parameter(Variability::Fixed)
        .start_integer(&[3])
        .after_set(resum),
];

#[test]
fn a_place_is_read_and_written_through_one_accessor_and_after_set_follows_each_write() {
    use robofmu_fmi::core::value_check::{Value, holds, write};
    let mut m = Kept::default();
    // Expected: the values written, read back through the same place; after_set ran
    // once per accepted write (counted), and sum = gain[1] + gain[2] by hand.
    write(&mut m, &KEPT[0], 1, 2, Value::Real(5.0)).unwrap();
    assert_eq!(m.gain, [0.0, 5.0]);
    assert_eq!((m.sum, m.changes), (5.0, 1));
    assert!(holds(&mut m, &KEPT[0], 1, Value::Real(5.0)));
    write(&mut m, &KEPT[1], 0, 3, Value::Boolean(true)).unwrap();
    assert!(m.on && m.changes == 1, "no hook declared: none ran");
    // The model's own writer refuses an even order: nothing stored, no hook.
    let refused = write(&mut m, &KEPT[2], 0, 4, Value::Integer(4)).unwrap_err();
    assert!(refused.contains("the order is odd"), "{refused}");
    assert_eq!((m.order, m.changes), (0, 1));
    write(&mut m, &KEPT[2], 0, 4, Value::Integer(5)).unwrap();
    assert_eq!((m.order, m.changes), (5, 2));
    // The FMI 2.0 scalars: all three writable, read through the place.
    let table = flatten(KEPT);
    assert!(table.iter().all(|v| v.has_setter()));
    let Kind::Real { get, .. } = &table[1].kind else {
        panic!("gain[2] is a Real")
    };
    assert_eq!(get.call(&mut m), 5.0);
}
