//! Holder crate for the workspace's integration tests; see `main.rs`.
