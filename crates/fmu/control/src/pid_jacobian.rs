//! The Jacobian of one PID channel ([`pid::output`] and [`pid::derivatives`]) in
//! closed form: the partial derivative
//! of the output u or a state derivative with respect to one input or state, at the
//! current gains, state and inputs. The limits make u flat, conditional integration
//! makes dI/dt flat; the channel reads nothing of another channel.

use crate::pid::{self, PidGains, PidInputs, PidState};

/// What the law computes: the output and the time derivatives of the two states.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unknown {
    Output,
    IntegralRate,
    FilterRate,
}

/// What the law reads: the five inputs and the two states.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Known {
    Setpoint,
    Measurement,
    SetpointRate,
    MeasuredRate,
    Feedforward,
    Integral,
    Filter,
}

/// d unknown / d known; `known` None is a variable the law does not read (a parameter):
/// 0 where the unknown is flat anyway, else None (no such partial derivative).
pub fn partial(
    g: &PidGains,
    s: &PidState,
    i: &PidInputs,
    unknown: Unknown,
    known: Option<Known>,
) -> Option<f64> {
    use Known::*;
    let out = pid::output(g, s, i);
    let error = matches!(known, Some(Setpoint | Measurement));
    let rate = matches!(known, Some(SetpointRate | MeasuredRate));
    let sign = if matches!(known, Some(Setpoint | SetpointRate)) {
        1.0
    } else {
        -1.0
    };
    match unknown {
        Unknown::Output
            if g.limits
                .is_some_and(|(lo, hi)| out.u_raw > hi || out.u_raw < lo) =>
        {
            Some(0.0)
        }
        Unknown::Output => {
            // Coefficients of e, of the rate error and of the filter state in the term D.
            let (d_e, d_rate, d_filter) = match (g.use_rate_inputs, g.tf > 0.0, g.kd != 0.0) {
                (true, true, _) => (0.0, 0.0, g.kd),
                (true, false, _) => (0.0, g.kd, 0.0),
                (false, _, true) => (g.kd / g.tf, 0.0, -g.kd / g.tf),
                (false, _, false) => (0.0, 0.0, 0.0),
            };
            Some(match known? {
                Setpoint | Measurement => sign * (g.kp + d_e),
                SetpointRate | MeasuredRate => sign * d_rate,
                Feedforward => 1.0,
                Integral => g.ki,
                Filter => d_filter,
            })
        }
        Unknown::IntegralRate => {
            let integrating = error && !pid::integration_stopped(g, &out);
            Some(if integrating { sign } else { 0.0 })
        }
        Unknown::FilterRate => Some(if !g.filter_active() {
            0.0
        } else if (error && !g.use_rate_inputs) || (rate && g.use_rate_inputs) {
            sign / g.tf
        } else if known == Some(Filter) {
            -1.0 / g.tf
        } else {
            0.0
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every input and state of one channel, as a point of the law's domain.
    fn perturbed(s: &PidState, i: &PidInputs, known: Known, d: f64) -> (PidState, PidInputs) {
        let (mut s, mut i) = (*s, *i);
        *match known {
            Known::Setpoint => &mut i.setpoint,
            Known::Measurement => &mut i.measurement,
            Known::SetpointRate => &mut i.setpoint_rate,
            Known::MeasuredRate => &mut i.measured_rate,
            Known::Feedforward => &mut i.feedforward,
            Known::Integral => &mut s.integral,
            Known::Filter => &mut s.filter,
        } += d;
        (s, i)
    }

    fn value(g: &PidGains, s: &PidState, i: &PidInputs, unknown: Unknown) -> f64 {
        let rates = pid::derivatives(g, s, i);
        match unknown {
            Unknown::Output => pid::output(g, s, i).u,
            Unknown::IntegralRate => rates.integral,
            Unknown::FilterRate => rates.filter,
        }
    }

    #[test]
    fn partials_match_central_differences() {
        // Expected values: central differences of pid::output / pid::derivatives, for
        // the error path, the filtered and the unfiltered rate path, and a saturated,
        // integration-stopped output (the law is piecewise linear: exact up to round-off).
        let (s, i) = (
            PidState {
                integral: 0.3,
                filter: -0.2,
            },
            PidInputs {
                setpoint: 1.0,
                measurement: 0.4,
                setpoint_rate: 0.5,
                measured_rate: -0.1,
                feedforward: 0.05,
            },
        );
        let base = PidGains {
            kp: 2.0,
            ki: 0.7,
            kd: 0.3,
            tf: 0.05,
            ..PidGains::default()
        };
        let cases = [
            base,
            PidGains {
                use_rate_inputs: true,
                ..base
            },
            PidGains {
                use_rate_inputs: true,
                tf: 0.0,
                ..base
            },
            PidGains {
                limits: Some((-0.5, 0.5)),
                ..base
            },
        ];
        let knowns = [
            Known::Setpoint,
            Known::Measurement,
            Known::SetpointRate,
            Known::MeasuredRate,
            Known::Feedforward,
            Known::Integral,
            Known::Filter,
        ];
        for g in &cases {
            for unknown in [Unknown::Output, Unknown::IntegralRate, Unknown::FilterRate] {
                for known in knowns {
                    let h = 1e-6;
                    let (sp, ip) = perturbed(&s, &i, known, h);
                    let (sm, im) = perturbed(&s, &i, known, -h);
                    let fd =
                        (value(g, &sp, &ip, unknown) - value(g, &sm, &im, unknown)) / (2.0 * h);
                    let exact = partial(g, &s, &i, unknown, Some(known)).unwrap();
                    assert!(
                        (fd - exact).abs() < 1e-7,
                        "{g:?} {unknown:?} {known:?}: {fd} vs {exact}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_parameter_has_no_partial_where_the_output_depends_on_it() {
        // u is linear in Kp e: d u / d Kp is not a partial the law defines (None), while
        // the saturated u and the state rates do not move with it (0).
        let (s, i) = (
            PidState::default(),
            PidInputs {
                setpoint: 1.0,
                ..PidInputs::default()
            },
        );
        let g = PidGains {
            kp: 1.0,
            tf: 0.05,
            ..PidGains::default()
        };
        assert_eq!(partial(&g, &s, &i, Unknown::Output, None), None);
        assert_eq!(partial(&g, &s, &i, Unknown::IntegralRate, None), Some(0.0));
        let limited = PidGains {
            limits: Some((-0.1, 0.1)),
            ..g
        };
        assert_eq!(partial(&limited, &s, &i, Unknown::Output, None), Some(0.0));
    }
}
