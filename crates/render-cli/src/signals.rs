//! SIGINT, SIGTERM and SIGHUP (Ctrl-C, `kill`, a closed terminal): stop the render and leave
//! no temporary file behind.
//!
//! The first signal cancels the render through its [`Cancel`] token (the workers stop within
//! one cell each) and removes every pending output's temporary file
//! ([`render::abandon_pending_outputs`]), so no output is replaced afterwards; `main` then
//! reports the interruption and exits with status 130. A second signal exits at once, with the
//! temporaries already gone.

use std::sync::atomic::{AtomicBool, Ordering};

use render::Cancel;

/// The exit status after an interrupted run: 128 + SIGINT, as shells report Ctrl-C.
pub(crate) const INTERRUPTED_EXIT: u8 = 130;

/// Installs the handler for the process (once; a second call is ignored).
pub(crate) fn install(cancel: &Cancel) {
    let cancel = cancel.clone();
    let again = AtomicBool::new(false);
    // `ctrlc` runs the handler on its own thread, outside signal context, so it may take
    // locks and touch files. Failure to install (another handler already set) only loses
    // the cleanup, never the render.
    let _ = ctrlc::set_handler(move || {
        if again.swap(true, Ordering::SeqCst) {
            std::process::exit(i32::from(INTERRUPTED_EXIT));
        }
        cancel.cancel();
        render::abandon_pending_outputs();
    });
}
