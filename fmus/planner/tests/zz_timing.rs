use robofmu_fmi::core::Model;
use robofmu_fmi::core::instance::{calculated_flags, model_with_start_values, sorted_table};
use robofmu_planner_fmu::Planner as P;
use std::time::Instant;
fn med(mut f: impl FnMut()) -> f64 {
    let mut t = Vec::new();
    for _ in 0..5000 {
        let s = Instant::now();
        f();
        t.push(s.elapsed().as_secs_f64() * 1e6);
    }
    t.sort_by(|a, b| a.partial_cmp(b).unwrap());
    t[t.len() / 2]
}
#[test]
fn timing() {
    println!(
        "variables {:.2}",
        med(|| {
            std::hint::black_box(P::variables());
        })
    );
    println!(
        "sorted {:.2}",
        med(|| {
            std::hint::black_box(sorted_table::<P>().unwrap());
        })
    );
    let t = sorted_table::<P>().unwrap();
    println!(
        "new {:.2}",
        med(|| {
            std::hint::black_box(P::new());
        })
    );
    println!(
        "start values {:.2}",
        med(|| {
            std::hint::black_box(model_with_start_values::<P>(&t).unwrap());
        })
    );
    println!(
        "flags {:.2}",
        med(|| {
            std::hint::black_box(calculated_flags(&t));
        })
    );
    println!(
        "build3 {:.2}",
        med(|| {
            std::hint::black_box(robofmu_fmi::fmi3::table::build::<P>(&t).unwrap());
        })
    );
    println!(
        "instance {:.2}",
        med(|| {
            std::hint::black_box(robofmu_fmi::core::Instance::<P>::new().unwrap());
        })
    );
    println!("len {}", t.len());
}
#[test]
fn size() {
    println!(
        "size {}",
        std::mem::size_of::<robofmu_fmi::core::Variable<P>>()
    );
}
