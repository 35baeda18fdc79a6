//! Markdown helpers for the report binaries, and atomic file output.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};

/// An error or tolerance in compact scientific notation (`0` for exact, `—` for none).
pub fn sci(v: f64) -> String {
    if v == 0.0 {
        "0".to_owned()
    } else if v.is_nan() {
        "—".to_owned()
    } else {
        format!("{v:.1e}")
    }
}

/// A Markdown table from a header and rows (cells are written as given).
pub fn table(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "| {} |", header.join(" | "));
    let _ = writeln!(s, "|{}", header.iter().map(|_| "---|").collect::<String>());
    for r in rows {
        let _ = writeln!(s, "| {} |", r.join(" | "));
    }
    s
}

/// Writes `text` to `path` through a temporary file in the same directory and a rename, so a
/// failed run never leaves a half-written report.
pub fn write_atomically(path: &Path, text: &str) -> Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let tmp = dir.join(format!(
        ".{}.tmp",
        path.file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("report")
    ));
    std::fs::write(&tmp, text).with_context(|| format!("cannot write {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("cannot replace {}", path.display()))
}

/// The current commit (`git rev-parse --short HEAD`), or `unknown`.
pub fn git_commit() -> String {
    std::process::Command::new("git")
        .args(["rev-parse", "--short", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_owned())
        .unwrap_or_else(|| "unknown".to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_and_numbers_render() {
        assert_eq!(sci(0.0), "0", "exact");
        assert_eq!(sci(1.21e-15), "1.2e-15", "one decimal");
        let t = table(&["a", "b"], &[vec!["1".into(), "2".into()]]);
        assert_eq!(t, "| a | b |\n|---|---|\n| 1 | 2 |\n", "pipe table");
    }
}
