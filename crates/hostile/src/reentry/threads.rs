//! A second thread on a busy instance (issue 20, defect 6): while thread A is inside
//! DoStep (its logger waits at the logCalls line), thread B calls DoStep on the same
//! instance and then frees it. Expected: B's DoStep is refused with Error (the
//! standard allows one thread per instance at a time; the FMU refuses instead of
//! racing), B's FreeInstance waits for A's call to return, A's DoStep returns Error
//! (its instance was freed meanwhile) without touching freed memory, and the handle
//! is dead afterwards.

use super::api::{Api, settable_real};
use super::calls::STEP;
use super::host::{Host, Trigger};
use super::{Outcome, expect, started};
use crate::binary::{ERROR, OK};
use std::sync::mpsc;

pub fn second_thread_then_free(api: &dyn Api) -> Outcome {
    let (to_b, inside) = mpsc::channel::<usize>();
    let (to_a, done) = mpsc::channel::<()>();
    std::thread::scope(|scope| {
        let a = scope.spawn(move || -> Result<(i32, String), String> {
            let host = Host::new();
            let h = started(api, &host)?;
            expect(
                api.log_all(h),
                OK,
                "SetDebugLogging (all categories)",
                &host,
            )?;
            host.arm(
                Trigger::Call(api.do_step_name()),
                Box::new(move |h| {
                    let _ = to_b.send(h as usize);
                    let _ = done.recv();
                    None
                }),
            );
            let status = api.do_step(h, 0.0, STEP);
            Ok((status, host.log_text()))
        });
        let Ok(h) = inside.recv() else {
            return match a.join() {
                Ok(Err(e)) => Err(e),
                _ => Err("thread A never reached its logger".into()),
            };
        };
        let h = h as super::api::Handle;
        let other = api.do_step(h, 0.0, STEP);
        api.free(h);
        let _ = to_a.send(());
        let (status, log) = a.join().map_err(|_| "thread A panicked".to_string())??;
        let after = api.get_real(h, settable_real(api.description()).0).0;
        let checks = [
            (other, ERROR, "thread B's DoStep while A is inside"),
            (status, ERROR, "thread A's DoStep (freed by B meanwhile)"),
            (after, ERROR, "a call on the handle after the deferred free"),
        ];
        for (got, want, what) in checks {
            if got != want {
                return Err(format!("{what} returned {got}, expected {want}: {log}"));
            }
        }
        if !log.contains("another thread") {
            return Err(format!("no log line for the refused thread: {log}"));
        }
        Ok("B refused with Error (logged); free deferred; A Error".into())
    })
}
