//! The benchmarks of the robot library and the analyses are this package's bench
//! targets (`cargo bench -p robofmu-benches`); benches/README.md lists them.
