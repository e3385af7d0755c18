//! Six PID channels against six independent scalar PIDs (the scalar law of `pid` and
//! the sampled scalar PID, one instance per channel): equal bit for bit, no channel
//! seeing another's inputs; counts, resizes and lengths refused with nothing changed.

use robofmu_control::pid::{self, PidGains, PidInputs, PidOutput, PidState};
use robofmu_control::pid_channels::{ChannelsError, MAX_CHANNELS, PidChannels};
use robofmu_control::sampled::SampledPid;

/// Six different channels: error path, rate path filtered and unfiltered, limits.
fn six() -> Vec<PidGains> {
    (0..6)
        .map(|k| {
            let kf = k as f64;
            PidGains {
                kp: 2.0 + kf,
                ki: 0.5 * (kf + 1.0),
                kd: 0.3 + 0.1 * kf,
                tf: if k == 4 { 0.0 } else { 0.02 + 0.01 * kf },
                limits: if k % 2 == 1 {
                    Some((-1.0 - kf, 0.8 + kf))
                } else {
                    None
                },
                use_rate_inputs: k >= 3,
            }
        })
        .collect()
}

fn inputs(tick: usize) -> Vec<PidInputs> {
    (0..6)
        .map(|k| {
            let t = tick as f64 * 1e-3;
            let kf = k as f64 + 1.0;
            PidInputs {
                setpoint: (kf * t).sin() + 0.2 * kf,
                measurement: 0.3 * (2.0 * kf * t).cos(),
                setpoint_rate: kf * (kf * t).cos(),
                measured_rate: -0.6 * kf * (2.0 * kf * t).sin(),
                feedforward: 0.05 * kf,
            }
        })
        .collect()
}

#[test]
fn six_channels_tick_as_six_scalar_sampled_pids() {
    // Truth: one SampledPid per channel with the same gains, ticked on its own inputs.
    let gains = six();
    let mut channels = PidChannels::new(&gains).unwrap();
    let mut scalars: Vec<SampledPid> = gains
        .iter()
        .map(|g| SampledPid::new(*g, 1e-3).unwrap())
        .collect();
    let mut out = vec![pid::output(&gains[0], &PidState::default(), &inputs(0)[0]); 6];
    let mut limited = 0;
    for tick in 0..3000 {
        let i = inputs(tick);
        channels.tick(&i, 1e-3, &mut out).unwrap();
        for k in 0..6 {
            let want = scalars[k].tick(&i[k]);
            assert_eq!(out[k], want, "tick {tick} channel {}", k + 1);
            assert_eq!(channels.states()[k], scalars[k].state());
            limited += usize::from(want.u != want.u_raw);
        }
    }
    assert!(limited > 100, "the limits were reached {limited} times");
}

#[test]
fn six_channels_are_the_scalar_continuous_law_per_channel() {
    // Truth: pid::output, pid::derivatives and pid::step per channel on its own state.
    let gains = six();
    let mut channels = PidChannels::new(&gains).unwrap();
    let states: Vec<PidState> = (0..6)
        .map(|k| PidState {
            integral: 0.1 * k as f64 - 0.2,
            filter: 0.05 * k as f64,
        })
        .collect();
    channels.set_states(&states).unwrap();
    let i = inputs(137);
    let mut out = vec![pid::output(&gains[0], &states[0], &i[0]); 6];
    let mut rates = vec![PidState::default(); 6];
    channels.outputs(&i, &mut out).unwrap();
    channels.derivatives(&i, &mut rates).unwrap();
    channels.step(&i, 0.013).unwrap();
    for k in 0..6 {
        assert_eq!(out[k], pid::output(&gains[k], &states[k], &i[k]));
        assert_eq!(rates[k], pid::derivatives(&gains[k], &states[k], &i[k]));
        assert_eq!(
            channels.states()[k],
            pid::step(&gains[k], &states[k], &i[k], 0.013)
        );
    }
    // No cross-talk: another input on channel 4 moves only output 4.
    let mut moved = i.clone();
    moved[3].setpoint += 1.0;
    let mut again = out.clone();
    channels.outputs(&moved, &mut again).unwrap();
    let before = {
        let mut o = out.clone();
        channels.outputs(&i, &mut o).unwrap();
        o
    };
    for k in 0..6 {
        assert_eq!(again[k] != before[k], k == 3, "channel {}", k + 1);
    }
}

#[test]
fn counts_out_of_range_and_bad_gains_are_refused_by_name() {
    let g = six()[0];
    assert_eq!(PidChannels::new(&[]), Err(ChannelsError::Count(0)));
    let too_many = vec![g; MAX_CHANNELS + 1];
    let e = PidChannels::new(&too_many).unwrap_err();
    assert!(e.to_string().contains("between 1 and 1024"), "{e}");
    let mut bad = six();
    bad[4].tf = -1.0;
    let e = PidChannels::new(&bad).unwrap_err();
    assert!(e.to_string().starts_with("channel 5: "), "{e}");

    let mut channels = PidChannels::new(&six()[..3]).unwrap();
    let states = [PidState {
        integral: 0.5,
        filter: -0.25,
    }; 3];
    channels.set_states(&states).unwrap();
    let unchanged = channels.clone();
    assert_eq!(channels.resize(0, g), Err(ChannelsError::Count(0)));
    assert_eq!(
        channels.resize(1_000_000_000, g),
        Err(ChannelsError::Count(1_000_000_000))
    );
    let e = channels
        .resize(6, PidGains { tf: f64::NAN, ..g })
        .unwrap_err();
    assert!(e.to_string().starts_with("channel 4: Tf"), "{e}");
    let e = channels.set_gains(3, g).unwrap_err();
    assert!(e.to_string().contains("no channel 4 of 3"), "{e}");
    assert_eq!(channels, unchanged);
    // A resize keeps the first channels' gains and states; new ones start at zero.
    channels.resize(6, g).unwrap();
    assert_eq!(channels.count(), 6);
    assert_eq!(&channels.states()[..3], &states);
    assert_eq!(channels.states()[5], PidState::default());
    assert_eq!(channels.gains()[5], g);
    channels.resize(2, g).unwrap();
    assert_eq!(channels.gains(), &six()[..2]);
}

#[test]
fn arrays_of_the_wrong_length_are_refused_with_nothing_changed() {
    let mut channels = PidChannels::new(&six()).unwrap();
    let unchanged = channels.clone();
    let five = &inputs(0)[..5];
    let mut out = vec![
        PidOutput {
            u: 0.0,
            u_raw: 0.0,
            error: 0.0,
            derivative_term: 0.0
        };
        6
    ];
    let e = channels.tick(five, 1e-3, &mut out).unwrap_err();
    assert_eq!(
        e.to_string(),
        "5 inputs given for 6 channels: pass one per channel"
    );
    let e = channels.tick(&inputs(0), 1e-3, &mut out[..4]).unwrap_err();
    assert!(e.to_string().starts_with("4 outputs"), "{e}");
    assert!(channels.step(five, 1e-3).is_err());
    assert!(channels.set_states(&[PidState::default(); 7]).is_err());
    for p in [0.0, -1.0, f64::NAN] {
        let e = channels.tick(&inputs(0), p, &mut out).unwrap_err();
        assert!(matches!(e, ChannelsError::Period(_)), "{e}");
    }
    assert_eq!(channels, unchanged);
    assert!(out.iter().all(|o| o.u == 0.0));
}
