#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""rfseek-live's checks of what it is asked before any device is opened: radio settings
that a source would ignore, and where each --set KEY=VALUE goes; and its progress line."""

import argparse
import math


def refuse_unused(args, serving=False):
    """Radio settings given where they would be ignored: a ValueError naming them, not a
    run that silently differs from what was asked. serving: the --zmq-serve process."""
    radio = {"--freq": args.freq, "--gain": args.gain, "--rate": args.rate,
             "--device": args.device or None}
    plan = {"--device-rate": args.device_rate, "--lo-offset": args.lo_offset}
    if serving:
        given, why = dict(radio, **plan), (
            "the served radio follows the table's plan for --radio, and the world's "
            "carrier and rate are scenario fields (--set carrier_hz=... --set "
            "samp_rate_hz=...)")
    elif args.source == "sim":
        # (A rehearsal's --gain is its simulated radio's, relative to the noise level.)
        given, why = ({k: v for k, v in radio.items() if k != "--gain"} if args.radio
                      else dict(radio, **plan)), (
            "the simulated world's carrier and sample rate are scenario fields (--set "
            "carrier_hz=... --set samp_rate_hz=...)%s" % (
                "" if args.radio else "; --device-rate and --lo-offset need --radio FAMILY"))
    elif args.source == "file":
        given, why = dict(radio, **plan), "the recording's metadata gives its carrier and rate"
    elif args.source == "zmq":
        given = {"--gain": args.gain, "--device": args.device or None, **plan}
        why = "the radio's settings belong to the --zmq-serve process"
    else:
        return
    if getattr(args, "fault", None) and not (serving or (args.source == "sim" and
                                                          args.radio)):
        raise ValueError("--fault: only in a rehearsal (--source sim --radio FAMILY, "
                         "or --zmq-serve), where the radio and the vehicle are simulated")
    kinds = [kind for kind, _ in getattr(args, "fault", None) or []]
    for kind in sorted(set(k for k in kinds if kinds.count(k) > 1)):
        raise ValueError("--fault %s: given twice; give each kind once" % kind)
    unused = [flag for flag, value in given.items() if value is not None]
    if unused:
        raise ValueError("%s: not used %s: %s" % (
            ", ".join(unused), "by --zmq-serve" if serving else
            "with --source %s" % args.source, why))


def fault(text):
    """--fault nav:DELAY[,JITTER[,DROPOUT[,EVERY]]] (seconds; state_to_nav's faults) or
    overflow:EVERY[,LOST] (LOST samples, 3000 by default, lost every EVERY s; the
    rehearsal's overflow_injector) or adc:unclipped (the simulated converter does not
    saturate: the reference of a clipping study) -> (kind, keyword arguments)."""
    kind, _, values = text.partition(":")
    if text == "adc:unclipped":
        return kind, {"clip": False}
    try:
        v = [float(x) for x in values.split(",")]
    except ValueError:
        v = []
    ok = bool(v) and all(math.isfinite(x) and x >= 0 for x in v)
    if kind == "nav" and ok and len(v) <= 4 and (len(v) < 3 or v[2] < (v[3] if len(v) == 4
                                                                       else 20.0)):
        return kind, dict(zip(("delay_s", "jitter_s", "dropout_s", "dropout_every_s"), v))
    if kind == "overflow" and ok and len(v) <= 2 and v[0] > 0 and (len(v) < 2 or v[1] >= 1):
        return kind, dict(zip(("every_s", "lost"), v))
    raise argparse.ArgumentTypeError(
        "%r: must be nav:DELAY[,JITTER[,DROPOUT[,EVERY]]] (seconds >= 0, a dropout shorter "
        "than its period, 20 s by default), overflow:EVERY[,LOST] (EVERY > 0 s, LOST >= 1 "
        "samples) or adc:unclipped" % text)


def split_sets(args, rfseek):
    """The --set KEY=VALUE items as (scenario items, seeker (key, value) pairs). With a
    simulated world a scenario key goes to the scenario (the seeker copies the fields
    they share); any other seeker key to the seeker configuration, with any source. A
    key of neither, or a scenario-only key without a simulated world, is a ValueError."""
    scen_keys, seek_keys = set(rfseek.scenario.keys()), set(rfseek.seeker_config.keys())
    simulated = args.source == "sim"
    scen, seek = [], []
    for kv in args.set:
        key, sep, value = kv.partition("=")
        key = key.strip()
        if not sep:
            raise ValueError("--set expects KEY=VALUE, got '%s'" % kv)
        if simulated and key in scen_keys:
            scen.append(kv)
        elif key in seek_keys:
            seek.append((key, value.strip()))
        elif key in scen_keys:
            raise ValueError("--set %s: a field of the simulated world, only with --source "
                             "sim" % key)
        else:
            raise ValueError("--set %s: unknown key. Seeker constants: %s. Scenario "
                             "fields (with --source sim): %s" % (
                                 key, ", ".join(sorted(seek_keys - scen_keys)),
                                 ", ".join(rfseek.scenario.keys())))
    return scen, seek


def compass_deg(rad):
    """The module's angle (counter-clockwise from east, rad) as a compass bearing,
    clockwise from north, in [0, 360) deg, as ground stations and autopilots give it."""
    return (90.0 - math.degrees(rad)) % 360.0


def progress_line(meas, telemetry, windows, wall_s):
    """One line of progress: the flight's time (the sample clock's, which a --speedup
    runs faster than the wall clock), the windows, the latest measurement and the
    commanded heading as a compass bearing."""
    return ("  flight %7.1f s  (wall %6.1f s)  %5d windows  f %9.2f Hz  snr %6.1f dB  "
            "stage %d  heading %05.1f deg%s" % (
                meas.get("time", 0.0), wall_s, windows, meas["freq_hz"], meas["snr_db"],
                telemetry["stage"], compass_deg(telemetry["heading"]),
                "" if meas["valid"] else "  (invalid)"))


def make_estimator(args, rfseek, rate, alignment, src=None):
    """doppler_estimator: period --slot x rate, the radio's band, its detection test and
    its full scale (src.full_scale(): clipped windows are never valid)."""
    period = args.period if args.period is not None else int(round(args.slot * rate))
    pfa = args.pfa if args.pfa is not None else (
        1e-3 if args.source in ("uhd", "osmosdr", "soapy", "zmq") else 0.0)
    band = getattr(args, "band", (0.0, 0.0))
    est = rfseek.doppler_estimator(rate, args.window_len, args.fft_len,
                                   interpolator=args.interpolator, alignment=alignment,
                                   period=period, min_freq=band[0], max_freq=band[1],
                                   threshold_db=args.threshold_db, pfa=pfa)
    est.set_full_scale(src.full_scale() if hasattr(src, "full_scale") else 0.0)
    return est


def gain_control(args, src):
    """--agc on (the default) with a radio or a rehearsal: a gain_loop that steps the
    radio's gain (from --gain, else the table's; a rehearsal's from 0 dB relative); None
    for files, ZeroMQ and the plain simulation, or --agc off."""
    if getattr(args, "agc", "off") != "on":
        return None
    from .gain_loop import gain_loop
    if hasattr(src, "radio") and hasattr(src.radio, "set_gain") and hasattr(src, "world"):
        start = src.radio.gain_db  # a rehearsal's sim_radio
        return gain_loop(src.radio.set_gain, start, start - 60.0)
    if hasattr(src, "set_gain") and hasattr(src, "radio"):  # radio_source
        lo, hi = src.radio.gain_db
        start = src._clamp_gain(args.gain)
        return gain_loop(src.set_gain, start, lo)
    return None
