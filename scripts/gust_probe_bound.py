#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""How well one probe cycle of `adaptive` can measure the bearing in gusts.

One cycle flies theta + delta, theta - delta, theta - delta, theta + delta, `slots`
beacons each, turning between them at the airframe's rate. Each beacon's frequency is
    f_i = A cos(u_i - e) + c + g(t_i) + w_i,
A = f_d,max, u_i the heading flown relative to theta, e the bearing error, c the carrier
offset, g the gust along the line of sight (a Gauss-Markov process: std `gust` m/s over
lambda, correlation time `tau`) and w white noise of `noise` Hz per beacon. Linearised at
e = 0, sin(e) is the coefficient of A sin(u_i).

Printed: the standard deviation of sin(e) from one cycle
  - for the fit `adaptive` makes (least squares on A sin u, an offset and a drift),
    with the gusts in the data: its actual scatter;
  - for the best linear unbiased fit (generalised least squares with the true gust and
    noise covariance, which the seeker does not know): the floor for any linear fit of
    one cycle.
Both are exact (covariances, no sampling). docs/seeker.md "Where the strong-wind loss
comes from" quotes them.

    scripts/gust_probe_bound.py --preset windy
    scripts/gust_probe_bound.py --gust 1 --tau 5 --slots 10,20,40 --deltas 5,10,20
"""

import argparse
import math
import sys

import numpy as np

C = 299792458.0


def cycle_headings(delta, slots, rate, slot_s):
    """Headings flown (relative to theta) over one +, -, -, + cycle, starting on +delta;
    rate (rad/s) <= 0: turns are instant."""
    out, cur = [], delta
    step = rate * slot_s if rate > 0.0 else math.inf
    for target in (delta, -delta, -delta, delta):
        for _ in range(slots):
            cur += max(-step, min(step, target - cur))
            out.append(cur)
    return np.array(out)


def sin_error_std(amp_hz, delta, slots, slot_s, rate, gust_hz, tau_s, noise_hz):
    """(least squares with offset and drift, generalised least squares): the standard
    deviation of sin(e) from one cycle."""
    u = cycle_headings(delta, slots, rate, slot_s)
    n = len(u)
    t = np.arange(n) * slot_s
    x = np.column_stack([amp_hz * np.sin(u), np.ones(n), t - t.mean()])
    lag = np.abs(t[:, None] - t[None, :])
    cov = noise_hz ** 2 * np.eye(n)
    if gust_hz > 0.0:
        cov = cov + gust_hz ** 2 * np.exp(-lag / tau_s)
    ols = np.linalg.pinv(x)
    v_ols = (ols @ cov @ ols.T)[0, 0]
    ci = np.linalg.inv(cov)
    gls = np.linalg.solve(x.T @ ci @ x, x.T @ ci)
    v_gls = (gls @ cov @ gls.T)[0, 0]
    return math.sqrt(v_ols), math.sqrt(v_gls)


def floats(text):
    return [float(v) for v in text.split(",") if v.strip()]


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--preset", default=None,
                   help="take the airspeed, carrier, gusts, slot and turn rate from this "
                        "scenario preset (rfseek.scenario.presets()); options given "
                        "explicitly win")
    p.add_argument("--speed", type=float, default=None, help="airspeed, m/s (10)")
    p.add_argument("--carrier", type=float, default=None, help="carrier, Hz (2e9)")
    p.add_argument("--gust", type=float, default=None, help="gust std per axis, m/s (1)")
    p.add_argument("--tau", type=float, default=None, help="gust correlation time, s (5)")
    p.add_argument("--noise", type=float, default=2.5,
                   help="white frequency noise per beacon, Hz (default 2.5)")
    p.add_argument("--slot", type=float, default=None, help="beacon period, s (0.05)")
    p.add_argument("--turn-rate", type=float, default=None,
                   help="turn rate between probes, deg/s (30; 0: instant)")
    p.add_argument("--slots", default="20", help="beacons per probe, comma-separated")
    p.add_argument("--deltas", default="5,10,20", help="probe half-angles, deg")
    a = p.parse_args(argv)
    given = {"speed": 10.0, "carrier": 2e9, "gust": 1.0, "tau": 5.0, "slot": 0.05,
             "turn_rate": 30.0}
    if a.preset:
        from gnuradio import rfseek
        sc = rfseek.scenario()
        try:
            sc.apply_preset(a.preset)
        except ValueError as e:
            p.error("--preset: %s" % e)
        rate = sc.turn_rate_rad_per_s
        if sc.bank_limit_rad > 0.0:
            # A bank-limited airframe: its steady rate at the bank limit (the roll in
            # and out is not modelled here), or the plain limit if that is lower.
            bank_rate = 9.80665 * math.tan(sc.bank_limit_rad) / sc.speed_mps
            rate = min(rate, bank_rate) if rate > 0.0 else bank_rate
        given.update(speed=sc.speed_mps, carrier=sc.carrier_hz, gust=sc.wind_gust_mps,
                     tau=sc.wind_gust_tau_s, slot=sc.slot_period_s,
                     turn_rate=math.degrees(rate))
    for key, value in given.items():
        if getattr(a, key) is None:
            setattr(a, key, value)
    for name, v in (("--speed", a.speed), ("--carrier", a.carrier), ("--tau", a.tau),
                    ("--slot", a.slot)):
        if not 0.0 < v < math.inf:
            p.error("%s must be > 0 and finite, got %g" % (name, v))
    for name, v in (("--gust", a.gust), ("--noise", a.noise), ("--turn-rate", a.turn_rate)):
        if not 0.0 <= v < math.inf:
            p.error("%s must be >= 0 and finite, got %g" % (name, v))
    if a.gust == 0.0 and a.noise == 0.0:
        p.error("--gust and --noise are both 0: nothing limits the fit")
    try:
        slot_list = [int(v) for v in a.slots.split(",")]
    except ValueError:
        p.error("--slots must be comma-separated integers >= 2, got %r" % a.slots)
    if not slot_list or min(slot_list) < 2 or max(slot_list) > 2000:
        p.error("--slots must be comma-separated integers in [2, 2000], got %r" % a.slots)
    try:
        delta_list = floats(a.deltas)
    except ValueError:
        p.error("--deltas must be comma-separated degrees in (0, 90), got %r" % a.deltas)
    if not delta_list or not all(0.0 < d < 90.0 for d in delta_list):
        p.error("--deltas must be comma-separated degrees in (0, 90), got %r" % a.deltas)
    lam = C / a.carrier
    amp, gust_hz = a.speed / lam, a.gust / lam
    print("f_d,max %.1f Hz, gust along the line of sight %.1f Hz (%g m/s) of %g s, white "
          "noise %g Hz per beacon, turns at %g deg/s"
          % (amp, gust_hz, a.gust, a.tau, a.noise, a.turn_rate))
    print("| beacons per probe | delta (deg) | std of sin(error): adaptive's fit | "
          "best linear fit (gusts known) | ratio |")
    print("| --- | --- | --- | --- | --- |")
    for slots in slot_list:
        for d in delta_list:
            o, g = sin_error_std(amp, math.radians(d), slots, a.slot,
                                 math.radians(a.turn_rate), gust_hz, a.tau, a.noise)
            print("| %d | %g | %.3f | %.3f | %.2f |" % (slots, d, o, g, o / g))
    return 0


if __name__ == "__main__":
    sys.exit(main())
