//! The value-reference index of a declared model is built once per library and shared
//! by its instances (`core::shared`: the model's own cell, defined by `share_index!`).
//! Truths: pointer identity of the index, the table's value references against the
//! declarations' scheme (pinned 10, then 11 and 12 for the unpinned array), and values
//! written to one instance not showing in another. The FMI 3.0 array and scalar-only
//! views are shared too, each in its own typed cell of the index: the array view has
//! `y` as one array of 2, the scalar view `y[1]`, `y[2]`.

use robofmu_fmi::core::instance::{Index, Instance};
use robofmu_fmi::core::value_check::Value;
use robofmu_fmi::core::{DefaultExperiment, Log, Model, ModelInfo, StepOutcome, Variability};
use robofmu_fmi::fmi3::instance::Instance as Instance3;
use robofmu_fmi::fmi3::logging::{Callback, Logger};
use robofmu_fmi::fmi3::mode::Interface;
use robofmu_fmi::prelude::Declaration;
use std::sync::Arc;

const EXPERIMENT: DefaultExperiment = DefaultExperiment {
    start_time: 0.0,
    stop_time: 1.0,
    tolerance: 1e-6,
    step_size: 0.1,
};

const fn info(name: &'static str) -> ModelInfo {
    ModelInfo {
        model_name: name,
        model_identifier: name,
        guid: "{shared-index}",
        description: "test model",
        default_experiment: EXPERIMENT,
        number_of_event_indicators: 0,
        log_categories: &[],
    }
}

/// A declared model: a gain k (pinned at 10) and a two-element output y = k u.
#[derive(Clone)]
struct Declared {
    k: f64,
}

static DECLARED: ModelInfo = info("Declared");
static DECLARATIONS: &[Declaration<Declared>] = &[
    Declaration::real("k", "gain", |m: &Declared, _| m.k)
        .at(10)
        .parameter(Variability::Tunable)
        .start_real(&[2.0])
        .set_real(|m, _, v| {
            m.k = v;
            Ok(())
        }),
    Declaration::real("y", "k times the element number", |m: &Declared, i| {
        m.k * (i + 1) as f64
    })
    .array(2)
    .output(),
];

macro_rules! trivial_model {
    () => {
        fn set_time(&mut self, _time: f64) {}
        fn exit_initialization(&mut self, _log: &dyn Log) -> Result<(), String> {
            Ok(())
        }
        fn do_step(&mut self, _time: f64, _step: f64, _log: &dyn Log) -> StepOutcome {
            StepOutcome::Completed
        }
    };
}

impl Default for Declared {
    fn default() -> Self {
        Declared { k: 0.0 }
    }
}

impl Model for Declared {
    const INFO: &'static ModelInfo = &DECLARED;
    const VARIABLES: &'static [Declaration<Self>] = DECLARATIONS;
    trivial_model!();
}

robofmu_fmi::share_index!(Declared);

#[test]
fn instances_of_a_declared_model_share_one_index_and_keep_their_own_values() {
    let new = || Instance::<Declared>::new(Index::shared().unwrap()).unwrap();
    let (mut a, mut b) = (new(), new());
    assert!(Arc::ptr_eq(a.index(), b.index()));
    let references: Vec<u32> = a.table().iter().map(|v| v.value_reference).collect();
    assert_eq!(references, [10, 11, 12]);
    a.write(10, Value::Real(3.0)).unwrap();
    a.prepare_read([12]).unwrap();
    assert_eq!(a.get_real(12).unwrap(), 6.0);
    assert_eq!(b.get_real(12).unwrap(), 4.0, "start value k = 2, element 2");
    drop(a);
    let c = new();
    assert!(
        Arc::ptr_eq(b.index(), c.index()),
        "kept after an instance is freed"
    );
}

/// An FMI 3.0 Model Exchange instance of the declared model (array or scalar view).
fn instance3(scalar: bool) -> Instance3<Declared> {
    let sink = Callback {
        function: None,
        environment: std::ptr::null_mut(),
    };
    let log = Logger::new(sink, Vec::new(), false);
    let accept = |_: &_, _| Ok(());
    let index = Index::shared().unwrap();
    match Instance3::<Declared>::new(Interface::ModelExchange, log, None, scalar, accept, index) {
        Ok(instance) => instance,
        Err(e) => panic!("{e}"),
    }
}

#[test]
fn fmi3_views_are_shared_per_view_and_kept_apart() {
    let (arrays, arrays_too) = (instance3(false), instance3(false));
    let (scalars, scalars_too) = (instance3(true), instance3(true));
    assert!(Arc::ptr_eq(&arrays.extra.table, &arrays_too.extra.table));
    assert!(Arc::ptr_eq(&scalars.extra.table, &scalars_too.extra.table));
    assert!(Arc::ptr_eq(arrays.core.index(), scalars.core.index()));
    let names = |t: &Instance3<Declared>| -> Vec<(String, usize)> {
        (t.extra.table.variables.iter())
            .map(|v| (v.name.to_string(), v.size()))
            .collect()
    };
    let expected = |list: &[(&str, usize)]| -> Vec<(String, usize)> {
        list.iter().map(|&(n, k)| (n.to_string(), k)).collect()
    };
    assert_eq!(names(&arrays), expected(&[("time", 1), ("k", 1), ("y", 2)]));
    assert_eq!(
        names(&scalars),
        expected(&[("time", 1), ("k", 1), ("y[1]", 1), ("y[2]", 1)])
    );
}
