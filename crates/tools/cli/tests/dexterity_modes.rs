//! The working mode is part of every dexterity answer (issue 14): the default fixed
//! mode of each manipulator is the one docs/dexterity.md argues for, and the CLI names
//! the mode of every figure it prints.

use robofmu_analyses::dexterity::gci::{GciGrid, gci};
use robofmu_analyses::dexterity::workspace::ModeChoice;
use robofmu_analyses::dexterity::{Manipulator, Robot, RobotKind};
use std::process::Command;

fn robofmu(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_robofmu"))
        .args(args)
        .output()
        .expect("run robofmu");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The leading number of a printed line.
fn leading(line: &str) -> f64 {
    line.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn default_mode_has_the_largest_gci_and_every_mode_reaches_the_same_poses() {
    // Truth: the GCI of every mode computed here on a coarse grid (30 x 30 x 17 cells
    // over phi in [10, 180] deg); the default modes are documented as the largest-GCI
    // ones (the 1-RRR's two modes tie: mirror-image elbows).
    let grid = GciGrid {
        xy_cells: 30,
        phi_cells: 17,
        phi_min: 10f64.to_radians(),
        phi_max: 180f64.to_radians(),
    };
    for kind in RobotKind::ALL {
        let robot = Robot::paper(kind);
        let per_mode: Vec<_> = (0..robot.working_modes())
            .map(|m| gci(&robot, &grid, ModeChoice::Only(m)).unwrap())
            .collect();
        let default = per_mode[kind.default_mode()];
        for (m, g) in per_mode.iter().enumerate() {
            assert!(g.value <= default.value + 1e-3, "{kind} mode {m}: {g:?}");
            assert_eq!(g.volume, default.volume, "{kind} mode {m}");
        }
    }
}

#[test]
fn max_lci_names_the_default_mode_and_all_lists_every_mode_and_the_best() {
    // Truth: the best over modes is the largest of the per-mode maxima on the same grid,
    // and mode 4 on the 2 cm grid is the paper's 0.5038 (crates/tools/analyses/tests/dexterity_reproduction.rs).
    let base = ["dexterity", "max-lci", "--robot", "3rrr", "--phi", "10"];
    let grid = ["--grid", "21"];
    let default = robofmu(&[&base[..], &grid[..]].concat());
    assert!(default.contains("3rrr, mode 7 (default)"), "{default}");
    let all = robofmu(&[&base[..], &grid[..], &["--mode", "all"]].concat());
    let lines: Vec<&str> = all.lines().collect();
    assert_eq!(lines.len(), 9, "{all}");
    for (m, line) in lines[..8].iter().enumerate() {
        assert!(line.contains(&format!("3rrr, mode {m}")), "{line}");
    }
    assert_eq!(leading(lines[4]), 0.5038);
    assert_eq!(leading(lines[7]), leading(&default));
    let largest = lines[..8].iter().map(|l| leading(l)).fold(0.0, f64::max);
    assert!(
        lines[8].contains("best over modes, attained in mode"),
        "{}",
        lines[8]
    );
    assert_eq!(leading(lines[8]), largest);
}

#[test]
fn gci_names_its_mode_and_best_is_an_option() {
    let base = [
        "dexterity",
        "gci",
        "--robot",
        "2rrr",
        "--cells",
        "20",
        "--phi-cells",
        "10",
    ];
    let default = robofmu(&base);
    assert!(default.contains("(2rrr, mode 3 (default);"), "{default}");
    let best = robofmu(&[&base[..], &["--mode", "best"]].concat());
    assert!(best.contains("(2rrr, best over modes;"), "{best}");
    // The best mode at each pose is at least every fixed mode there.
    assert!(leading(&best) >= leading(&default));
}
