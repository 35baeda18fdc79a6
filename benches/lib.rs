//! Holder crate for the workspace's benchmarks and report binaries.
