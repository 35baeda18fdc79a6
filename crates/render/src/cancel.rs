//! [`Cancel`]: a token that stops a render from another thread (Ctrl-C in the `render`
//! program, a dropped request in a server).
//!
//! The pixel loop checks the token before every cell (a pixel, or Stam's preview cell of
//! `rx × ry` pixels), so a cancelled render stops within one cell's rays per worker thread;
//! a ray already being traced is finished, because the root finders have no cancellation
//! points. A cancelled render returns [`Cancelled`] and no image.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// A shared cancellation flag: cheap to clone (every clone is the same flag), checked with a
/// relaxed atomic load.
///
/// # Examples
/// ```
/// let cancel = render::Cancel::new();
/// let remote = cancel.clone();
/// assert!(!cancel.is_cancelled());
/// remote.cancel();
/// assert!(cancel.is_cancelled(), "every clone sees the request");
/// ```
#[derive(Clone, Debug, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    /// A token that is not cancelled.
    pub fn new() -> Self {
        Cancel::default()
    }

    /// Asks every render holding a clone of this token to stop. Idempotent.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether [`Cancel::cancel`] was called on this token or a clone.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// Whether `other` is a clone of this token (the same request), not merely in the same
    /// state.
    pub fn is_same(&self, other: &Cancel) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }

    /// `Err(Cancelled)` once cancelled.
    pub fn check(&self) -> Result<(), Cancelled> {
        if self.is_cancelled() {
            Err(Cancelled)
        } else {
            Ok(())
        }
    }
}

/// The render was stopped through its [`Cancel`] token.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the render was cancelled")]
pub struct Cancelled;
