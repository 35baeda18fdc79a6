//! The `render` command line: renders a scene file to a PNG (filled in with the tracer).

fn main() {}
