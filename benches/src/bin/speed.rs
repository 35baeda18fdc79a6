//! Run time against error (placeholder while the stability suite is built).
fn main() {}
