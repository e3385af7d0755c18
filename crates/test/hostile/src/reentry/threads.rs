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

/// FMI 3.0, models with intermediate points (issue 36): while fmi3DoStep waits in
/// the intermediateUpdate callback (thread A), thread B calls fmi3GetFloat64 on the
/// instance, and the callback returns while B is still inside (B's logger waits at
/// its logCalls line; B reads a variable declared intermediateUpdate, legal there).
/// Expected: the resume is refused (Error, "another thread"),
/// and the instance is left in the Error state the standard's fmi3Error means, so
/// the first fmi3Reset works (OK) and the instance steps again. Before the fix it
/// stayed in Intermediate Update Mode: the first Reset returned Error (illegal
/// there), the second worked.
pub fn get_while_resuming(api: &dyn Api) -> Outcome {
    // A Real B may read there (so that B's call itself succeeds and leaves the mode).
    let readable = api
        .description()
        .of_type(crate::description::VarType::Real)
        .find(|v| v.intermediate_update)
        .map(|v| v.vr);
    let Some(vr) = readable else {
        return Ok("not applicable: no variable declared intermediateUpdate".into());
    };
    let (to_b, go) = mpsc::channel::<usize>();
    let (b_inside, inside) = mpsc::channel::<()>();
    let (release_b, release) = mpsc::channel::<()>();
    let (b_done, done) = mpsc::channel::<()>();
    std::thread::scope(|scope| {
        let a = scope.spawn(move || -> Result<Option<[i32; 4]>, String> {
            let host = Host::new();
            let Some(h) = api.instantiate_with_update(&host) else {
                return Ok(None);
            };
            host.handle.set(h);
            expect(api.initialize(h, 0.0), OK, "initialize", &host)?;
            expect(api.log_all(h), OK, "SetDebugLogging", &host)?;
            let host_address = &*host as *const Host as usize;
            host.arm(
                Trigger::Intermediate,
                Box::new(move |h| {
                    // SAFETY: the host outlives the step that runs this hook.
                    let host = unsafe { &*(host_address as *const Host) };
                    host.arm(
                        Trigger::Call("fmi3GetFloat64"),
                        Box::new(move |_| {
                            let _ = b_inside.send(());
                            let _ = release.recv();
                            None
                        }),
                    );
                    let _ = to_b.send(h as usize);
                    let _ = inside.recv();
                    None
                }),
            );
            let step = api.do_step(h, 0.0, STEP);
            if !host.fired.get() {
                // No intermediate point: drop the hook (and its sender), so that B
                // stops waiting.
                host.arm(Trigger::Never, Box::new(|_| None));
                api.free(h);
                return Ok(None);
            }
            let _ = release_b.send(());
            let _ = done.recv();
            let reset = api.reset(h);
            let again = api.initialize(h, 0.0);
            let step_again = api.do_step(h, 0.0, STEP);
            let logged = host.logged("another thread");
            api.free(h);
            if !logged {
                return Err(format!(
                    "no log line for the refused resume: {}",
                    host.log_text()
                ));
            }
            Ok(Some([step, reset, again, step_again]))
        });
        if let Ok(h) = go.recv() {
            api.get_real(h as super::api::Handle, vr);
            let _ = b_done.send(());
        }
        let Some(statuses) = a.join().map_err(|_| "thread A panicked".to_string())?? else {
            return Ok("not applicable: no intermediateUpdate or no intermediate points".into());
        };
        let want = [ERROR, OK, OK, OK];
        let what = [
            "the step whose resume was refused",
            "the first Reset after it",
            "initializing again",
            "a step after that",
        ];
        for ((got, want), what) in statuses.into_iter().zip(want).zip(what) {
            if got != want {
                return Err(format!("{what} returned {got}, expected {want}"));
            }
        }
        Ok("resume refused (Error, logged); the first Reset OK; steps again".into())
    })
}
