//! A sample's panic caught as its message, so that one sample never aborts
//! a scan (it becomes a `diverged` row).

use std::cell::{Cell, RefCell};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Once;

thread_local! {
    static CAPTURING: Cell<bool> = const { Cell::new(false) };
    static CAUGHT: RefCell<Option<String>> = const { RefCell::new(None) };
}

fn payload_text(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "non-string panic payload".into()
    }
}

/// Runs `f`, turning a panic into `Err("panicked at FILE:LINE:COL: MESSAGE")`
/// without printing it (other threads' panics still print as usual).
pub(crate) fn catch_panic<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if CAPTURING.get() {
                let at = info
                    .location()
                    .map(|l| format!(" at {}:{}:{}", l.file(), l.line(), l.column()))
                    .unwrap_or_default();
                CAUGHT.set(Some(format!(
                    "panicked{at}: {}",
                    payload_text(info.payload())
                )));
            } else {
                default(info);
            }
        }));
    });
    let was = CAPTURING.replace(true);
    let result = catch_unwind(AssertUnwindSafe(f));
    CAPTURING.set(was);
    result.map_err(|payload| {
        CAUGHT
            .take()
            .unwrap_or_else(|| format!("panicked: {}", payload_text(&*payload)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn catch_panic_reports_message_and_location() {
        let e = catch_panic(|| -> u8 { panic!("kaboom {}", 7) }).unwrap_err();
        assert!(
            e.starts_with("panicked at ") && e.ends_with("kaboom 7"),
            "{e}"
        );
        assert!(e.contains("panic.rs"), "{e}");
        assert_eq!(catch_panic(|| 5), Ok(5));
    }
}
