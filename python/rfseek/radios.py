#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Radios: one table of what each receiver family can do, and the receive chain built
from it.

RADIOS (family -> radio) holds each family's documented receive rates, tuning range,
gain range, the device rate and LO offset the module uses, and for transmitters the
same for the beacon. The examples, ``rfseek-live`` and docs/live.md all read it (a
test checks the docs table against it), so a saved flowgraph cannot ask a radio for a
rate or frequency it cannot give.

``rx_plan(family, ...)`` turns it into settings: the device rate, the integer
decimation to the estimator's rate, the LO offset (the tuned centre sits that far from
the beacon, so the receiver's DC spike and its 1/f noise fall outside the band the
estimator searches) and the search band. ``radio_rx_chain`` is the DSP after the device
(a low-pass, LO-shifting, decimating FIR filter, then ``rx_rate`` set to the rate the
device actually granted divided by the decimation, which doppler_estimator follows);
``radio_source`` opens the device (gr-uhd, gr-osmosdr or gr-soapy) and feeds it through
that chain; ``sim_radio`` stands in for a device without hardware: the world's beacon at
the device's rate with its impairments (LO offset, DC offset, IQ imbalance, ADC
quantisation).
"""

import math

import numpy
import pmt
from dataclasses import dataclass

from gnuradio import blocks, filter, gr
from gnuradio.fft import window
from gnuradio.filter import firdes


@dataclass(frozen=True)
class radio:
    """A receiver (and transmitter) family: documented ranges and the module's choice."""
    family: str
    label: str
    driver: str            # "uhd", "osmosdr" or "soapy"
    device_args: str       # default device arguments
    tune_hz: tuple         # (lowest, highest) centre frequency
    rx_rates: tuple        # ((lo, hi), ...) receive rates the device accepts (S/s)
    rate_rule: str         # how a rate within the ranges is made (for the docs)
    rx_rate: float         # the device rate the module asks for
    lo_offset_hz: float    # tuned centre minus beacon frequency
    gain_db: tuple         # (lowest, highest) receive gain
    gain_default: float
    ddc: bool              # the device shifts by the LO offset in its own DSP (UHD)
    adc_bits: int          # sample resolution (the rehearsal's quantisation)
    ppm: float             # the receiver's reference accuracy (+-ppm)
    tx_rates: tuple = ()   # ((lo, hi), ...) transmit rates; () if it cannot transmit
    tx_rate: float = 0.0   # the transmit rate the beacon examples use
    tx_gain_db: tuple = ()
    notes: str = ""

    def accepts_rate(self, rate, tx=False):
        """Whether `rate` lies in one of the documented receive (transmit) ranges."""
        return any(lo <= rate <= hi for lo, hi in (self.tx_rates if tx else self.rx_rates))

    def tunes(self, freq):
        return self.tune_hz[0] <= freq <= self.tune_hz[1]


RADIOS = {r.family: r for r in (
    radio("usrp_b2xx", "USRP B200/B210/B200mini/B205mini", "uhd", "type=b200",
          (70e6, 6e9), ((62.5e3, 56e6),),
          "master clock (32 MHz by default) / an integer", 1e6, 250e3, (0.0, 76.0), 40.0,
          True, 12, 2.0, ((62.5e3, 56e6),), 1e6, (0.0, 89.8),
          "LO offset by UHD's tune request: the DSP brings the beacon to 0 Hz, the DC "
          "leak stays 250 kHz away for the host filter"),
    radio("usrp_n2xx_x3xx", "USRP N200/N210, X300/X310", "uhd", "",
          (10e6, 6e9), ((195.3125e3, 25e6),),
          "100 MHz (N2xx) or 200 MHz (X3xx) / an integer; a 184.32 MHz X3xx clock "
          "coerces 1 MS/s to 1.0017 MS/s (/184)", 1e6, 250e3, (0.0, 31.5), 20.0,
          True, 14, 2.5, ((195.3125e3, 25e6),), 1e6, (0.0, 31.5),
          "tuning and gain are the daughterboard's (UBX shown: 10 MHz-6 GHz, 0-31.5 dB; "
          "WBX 50 MHz-2.2 GHz, SBX 400 MHz-4.4 GHz); no rate below about 195 kS/s"),
    radio("rtlsdr", "RTL-SDR (RTL2832U + R820T/T2)", "osmosdr", "rtl=0",
          (24e6, 1766e6), ((225001.0, 300e3), (900001.0, 3.2e6)),
          "28.8 MHz / a ratio; above 2.4 MS/s samples are lost", 1.2e6, 250e3,
          (0.0, 49.6), 30.0, False, 8, 25.0,
          notes="receive only; no DC-removing DSP: the tone is held 250 kHz off the "
                "tuned centre"),
    radio("hackrf", "HackRF One", "osmosdr", "hackrf=0",
          (1e6, 6e9), ((2e6, 20e6),),
          "any rate in the range (the baseband filter at 1.75 MHz or more)", 2e6, 400e3,
          (0.0, 40.0), 24.0, False, 8, 20.0, ((2e6, 20e6),), 2e6, (0.0, 47.0),
          "gain is the LNA (IF) gain, 0-40 dB in 8 dB steps, VGA fixed at 20 dB; "
          "half duplex"),
    radio("plutosdr", "ADALM-PLUTO (AD9363), via SoapySDR", "soapy", "driver=plutosdr",
          (325e6, 3.8e9), ((521e3, 61.44e6),),
          "any rate in the range (below 2.083 MS/s the AD9363's FIR decimates)", 1e6,
          250e3, (0.0, 73.0), 40.0, False, 12, 25.0, ((521e3, 61.44e6),), 1e6,
          (0.0, 89.0),
          "gr-soapy (GNU Radio 3.10) with SoapyPlutoSDR; 70 MHz-6 GHz only on "
          "re-flashed units (AD9364 mode)"),
)}


def radio_for(family):
    """The table entry for `family`; ValueError naming the families otherwise."""
    try:
        return RADIOS[family]
    except (KeyError, TypeError):
        raise ValueError("radio family = %r: must be one of %s"
                         % (family, ", ".join(sorted(RADIOS)))) from None


@dataclass(frozen=True)
class rx_settings:
    """Receive settings for one family, beacon frequency and estimator rate."""
    family: str
    freq_hz: float          # the beacon's carrier
    device_rate: float      # asked of the device
    decimation: int
    out_rate: float         # the estimator's rate (device_rate / decimation)
    lo_offset_hz: float     # tuned centre - freq_hz
    center_hz: float        # what the device is tuned to (freq_hz + lo_offset_hz)
    taps: tuple             # the decimating low-pass filter
    band_hz: tuple          # (min, max) search band around the beacon; (0, 0): whole


def _finite(name, value, low=-math.inf):
    """`value` as a finite float >= low; ValueError naming `name` otherwise (None, a
    string, NaN or infinity included)."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        x = math.nan
    if not (math.isfinite(x) and x >= low):
        raise ValueError("%s = %r: must be a finite number%s"
                         % (name, value, "" if low == -math.inf else " >= %g" % low))
    return x


def rx_plan(family, freq_hz=2.4e9, out_rate=100e3, device_rate=None, lo_offset_hz=None,
            beacon_ppm=2.0, max_speed_mps=30.0):
    """Settings for receiving a beacon at `freq_hz` with `family` and measuring it at
    `out_rate` (about 100 kS/s: the paper's N = 1000 in 10 ms). The search band holds
    the two oscillators' offsets (the radio's ppm and `beacon_ppm`) and the Doppler of
    `max_speed_mps`, plus 1 kHz; the whole band when that is wider than 0.9 x out_rate.
    Raises ValueError naming the parameter when the device cannot do it."""
    r = radio_for(family)
    freq_hz = _finite("freq", freq_hz)
    out_rate = _finite("out_rate", out_rate)
    beacon_ppm = _finite("beacon_ppm", beacon_ppm)
    max_speed_mps = _finite("max_speed_mps", max_speed_mps, 0.0)
    if not r.tunes(freq_hz):
        raise ValueError("freq = %.6g Hz: the %s tunes %.6g-%.6g Hz"
                         % (freq_hz, r.label, r.tune_hz[0], r.tune_hz[1]))
    rate = r.rx_rate if device_rate is None else _finite("device_rate", device_rate)
    if not r.accepts_rate(rate):
        raise ValueError("device_rate = %.6g S/s: the %s accepts %s" % (
            rate, r.label, " or ".join("%.6g-%.6g" % lh for lh in r.rx_rates)))
    if not out_rate > 0:
        raise ValueError("out_rate = %r: must be > 0" % out_rate)
    dec = int(round(rate / out_rate))
    if dec < 1 or abs(dec * out_rate - rate) > 1e-6 * rate:
        raise ValueError("out_rate = %.6g S/s: must divide the device rate %.6g S/s by an "
                         "integer" % (out_rate, rate))
    lo = r.lo_offset_hz if lo_offset_hz is None else _finite("lo_offset", lo_offset_hz)
    if not r.tunes(freq_hz + lo):
        raise ValueError("lo_offset = %.6g Hz: puts the tuned centre outside the %s's "
                         "%.6g-%.6g Hz" % (lo, r.label, r.tune_hz[0], r.tune_hz[1]))
    # The DC leak, lo_offset from the beacon, must stay inside the device's band (where
    # the host filter removes it, rather than fold back onto the beacon), and without a
    # DDC the beacon is shifted there digitally: both need room for the filter's skirt.
    if abs(lo) + 0.5 * out_rate > 0.4 * rate:
        raise ValueError("lo_offset = %.6g Hz: |lo_offset| + out_rate / 2 must be within "
                         "0.4 x the device rate (%.6g Hz)" % (lo, 0.4 * rate))
    # The low-pass is flat over the output band's inner 90 % and stops from 55 % of the
    # output rate, so the noise after decimation stays white (the detection test assumes
    # it) and the DC spike, lo_offset away, is in the stop band.
    taps = tuple(firdes.low_pass(1.0, rate, 0.5 * out_rate, 0.1 * out_rate,
                                 window.WIN_BLACKMAN_HARRIS)) if dec > 1 else (1.0,)
    half = (r.ppm + abs(beacon_ppm)) * 1e-6 * freq_hz + \
        max_speed_mps * freq_hz / 299792458.0 + 1e3
    band = (-half, half) if half < 0.45 * out_rate else (0.0, 0.0)
    return rx_settings(family, float(freq_hz), rate, dec, rate / dec, lo,
                       freq_hz + lo, taps, band)


class rate_retag(gr.sync_block):
    """Passes samples through; sets rx_rate to the rate at its output: an rx_rate tag at
    the first sample (out_rate), unless one comes from upstream, and every upstream
    rx_rate tag times `factor` (1 / decimation after a decimating filter, which moves
    tags but not their values; the interpolation after an interpolating one)."""

    def __init__(self, out_rate, factor):
        gr.sync_block.__init__(self, "rate_retag", [numpy.complex64],
                               [numpy.complex64])
        self.set_tag_propagation_policy(gr.TPP_DONT)
        self.out_rate = float(out_rate)
        self.factor = float(factor)
        self.key = None

    def work(self, input_items, output_items):
        import pmt
        if self.key is None:
            self.key = pmt.intern("rx_rate")
        n = len(output_items[0])
        output_items[0][:] = input_items[0][:n]
        base = self.nitems_read(0)
        seen_rate = False
        for t in self.get_tags_in_window(0, 0, n):
            value = t.value
            if pmt.eqv(t.key, self.key):
                seen_rate = True
                if pmt.is_real(value):
                    value = pmt.from_double(pmt.to_double(value) * self.factor)
            self.add_item_tag(0, t.offset, t.key, value)
        if base == 0 and n > 0 and not seen_rate:
            self.add_item_tag(0, 0, self.key, pmt.from_double(self.out_rate))
        return n


class radio_rx_chain(gr.hier_block2):
    """The DSP after a device: the beacon shifted from -lo_offset to 0 Hz (unless the
    device's DDC did it), low-pass filtered and decimated to the estimator's rate, and
    rx_rate set to granted_rate / decimation."""

    def __init__(self, settings, granted_rate=None, ddc=False):
        gr.hier_block2.__init__(self, "radio_rx_chain",
                                gr.io_signature(1, 1, gr.sizeof_gr_complex),
                                gr.io_signature(1, 1, gr.sizeof_gr_complex))
        self.settings = settings
        self.granted_rate = float(granted_rate or settings.device_rate)
        shift = 0.0 if ddc else -settings.lo_offset_hz
        self.filter = filter.freq_xlating_fir_filter_ccc(
            settings.decimation, list(settings.taps), shift, self.granted_rate)
        self.retag = rate_retag(self.granted_rate / settings.decimation,
                                1.0 / settings.decimation)
        self.connect(self, self.filter, self.retag, self)

    def out_rate(self):
        """The rate at the output: the device's granted rate / the decimation."""
        return self.granted_rate / self.settings.decimation


def open_device(settings, device_args=None, gain=None, antenna=""):
    """Open the family's device at `settings` and return (block, granted rate, setters),
    setters a dict of callables: freq(f) and gain(g). LookupError when the driver or the
    device is missing (the message says which)."""
    r = radio_for(settings.family)
    args = r.device_args if device_args is None else device_args
    g = r.gain_default if gain is None else gain
    if r.driver == "uhd":
        try:
            from gnuradio import uhd
        except ImportError as e:
            raise LookupError("gr-uhd is not installed (%s)" % e)
        try:
            src = uhd.usrp_source(args, uhd.stream_args(cpu_format="fc32", channels=[0]))
        except RuntimeError as e:
            raise LookupError("no UHD device found (%s)" % " ".join(str(e).split()))
        src.set_samp_rate(settings.device_rate)
        if antenna:
            src.set_antenna(antenna, 0)

        def tune(f):
            src.set_center_freq(uhd.tune_request(f, settings.lo_offset_hz), 0)
        tune(settings.freq_hz)
        src.set_gain(g, 0)
        return src, src.get_samp_rate(), {"freq": tune, "gain": lambda v: src.set_gain(v, 0)}
    if r.driver == "osmosdr":
        try:
            import osmosdr
        except ImportError as e:
            raise LookupError("gr-osmosdr is not installed (%s)" % e)
        try:
            src = osmosdr.source(args="numchan=1 " + args)
        except RuntimeError as e:
            raise LookupError("no osmosdr device found (%s)" % " ".join(str(e).split()))
        src.set_sample_rate(settings.device_rate)
        src.set_dc_offset_mode(1, 0)  # automatic where the device supports it

        def tune(f):
            src.set_center_freq(f + settings.lo_offset_hz, 0)
        tune(settings.freq_hz)
        if r.family == "hackrf":
            setters = {"gain": lambda v: src.set_if_gain(v, 0)}
            src.set_bb_gain(20.0, 0)
        else:
            setters = {"gain": lambda v: src.set_gain(v, 0)}
        setters["gain"](g)
        if antenna:
            src.set_antenna(antenna, 0)
        setters["freq"] = tune
        return src, src.get_sample_rate(), setters
    try:
        from gnuradio import soapy
    except ImportError as e:
        raise LookupError("gr-soapy is not installed (%s)" % e)
    try:
        src = soapy.source(args, "fc32", 1, "", "", [""], [""])
    except RuntimeError as e:
        raise LookupError("no SoapySDR device found for '%s' (%s)"
                          % (args, " ".join(str(e).split())))
    src.set_sample_rate(0, settings.device_rate)
    # As GNU Radio's own PlutoSDR block: manual gain (not the AGC the last user may have
    # left) and the analog bandwidth of the stream.
    if src.has_gain_mode(0):
        src.set_gain_mode(0, False)
    src.set_bandwidth(0, settings.device_rate)

    def tune(f):
        src.set_frequency(0, f + settings.lo_offset_hz)
    tune(settings.freq_hz)
    src.set_gain(0, g)
    if antenna:
        src.set_antenna(0, antenna)
    return src, src.get_sample_rate(0), {"freq": tune, "gain": lambda v: src.set_gain(0, v)}


class radio_source(gr.hier_block2):
    """A radio of the table receiving the beacon at `freq`, its samples at the
    estimator's rate (`out_rate`, exactly the granted device rate / the decimation, with
    an rx_rate tag saying so), the beacon centred at 0 Hz and the DC spike filtered out.
    ``band()`` is the search band for doppler_estimator. Message port `command` (in):
    dicts with "gain" (dB) and/or "freq" (Hz), as UHD's sources take them (gain_loop's
    output); anything else is logged, counted (``dropped_commands()``) and dropped.
    LookupError when the device (or its driver) is missing, ValueError for settings the
    device cannot do."""

    def __init__(self, family="usrp_b2xx", freq=2.4e9, gain=None, out_rate=100e3,
                 device_args=None, lo_offset=None, device_rate=None, antenna=""):
        gr.hier_block2.__init__(self, "radio_source", gr.io_signature(0, 0, 0),
                                gr.io_signature(1, 1, gr.sizeof_gr_complex))
        self.radio = radio_for(family)
        self.settings = rx_plan(family, freq, out_rate, device_rate, lo_offset)
        self.device, granted, self._set = open_device(self.settings, device_args,
                                                      self._clamp_gain(gain), antenna)
        if abs(granted - self.settings.device_rate) > 1e-9 * self.settings.device_rate:
            gr.log.warn("radio_source: asked %.6f S/s, the device gave %.6f S/s: the "
                        "estimator follows the rx_rate tag (%.6f S/s)" % (
                            self.settings.device_rate, granted,
                            granted / self.settings.decimation))
        self.chain = radio_rx_chain(self.settings, granted, self.radio.ddc)
        self.connect(self.device, self.chain, self)
        self.commands = _commands({"gain": self.set_gain, "freq": self.set_freq})
        self.message_port_register_hier_in("command")
        self.msg_connect(self, "command", self.commands, "command")

    def dropped_commands(self):
        return self.commands.dropped

    def _clamp_gain(self, gain):
        lo, hi = self.radio.gain_db
        if gain is None:
            return self.radio.gain_default
        try:
            value = float(gain)
        except (TypeError, ValueError):
            value = math.nan
        if not math.isfinite(value):
            raise ValueError("radio_source: gain = %r: must be a number of dB (the %s's "
                             "%.1f-%.1f dB; outside it is clamped) or None for its "
                             "default" % (gain, self.radio.label, lo, hi))
        gain = value
        if not lo <= gain <= hi:
            gr.log.warn("radio_source: gain %.1f dB outside the %s's %.1f-%.1f dB: "
                        "clamped" % (gain, self.radio.label, lo, hi))
        return min(max(gain, lo), hi)

    def out_rate(self):
        return self.chain.out_rate()

    def granted_rate(self):
        return self.chain.granted_rate

    def full_scale(self):
        """The device's full scale in the output's units (complex64 from the drivers:
        1.0; the chain's filter passes the beacon at unit gain)."""
        return 1.0

    def band(self):
        return self.settings.band_hz

    def set_gain(self, gain):
        """GRC callback: receive gain (dB), clamped to the family's range."""
        self._set["gain"](self._clamp_gain(gain))

    def set_freq(self, freq):
        """GRC callback: retune to a beacon at `freq` (Hz; the LO offset kept)."""
        if not (self.radio.tunes(freq) and self.radio.tunes(freq + self.settings.lo_offset_hz)):
            raise ValueError("freq = %.6g Hz: the %s tunes %.6g-%.6g Hz" % (
                freq, self.radio.label, self.radio.tune_hz[0], self.radio.tune_hz[1]))
        self._set["freq"](freq)


class sim_radio(gr.hier_block2):
    """A device that is not there: the beacon at baseband (the world's, at `in_rate`)
    as the family's radio would deliver it at the planned device rate: interpolated to the device rate, shifted to -lo_offset (where a radio
    tuned lo_offset above the beacon hears it), plus a DC offset (`dc`, complex,
    relative to full scale) and IQ imbalance (`iq_gain_db`, `iq_phase_deg`); a DDC radio
    (UHD) shifts the beacon back to 0 Hz in its own DSP, leaving the leak at +lo_offset.
    Then quantisation to
    the family's ADC bits, the gain set so that the input's noise (`noise_rms`, per
    complex sample) is `noise_lsb` steps of the ADC (8: the noise floor 18 dB above the
    quantisation's, as docs/live.md advises) at gain_db 0. gain_db (set_gain at run time)
    scales the beacon and its noise before the converter, as a radio's receive gain does:
    a strong beacon clips at full scale (each of I and Q saturates at the converter's
    largest code). clip=False keeps the steps but lifts that limit to a 16-bit
    container's, 24 dB or more higher (a reference for clipping studies: the same radio
    with a converter that does not saturate). Feed its
    output to radio_rx_chain(settings)."""

    def __init__(self, settings, in_rate=100e3, noise_rms=1.0, noise_lsb=8.0,
                 dc=0.05 + 0.03j, iq_gain_db=0.5, iq_phase_deg=2.0, gain_db=0.0,
                 clip=True):
        gr.hier_block2.__init__(self, "sim_radio",
                                gr.io_signature(1, 1, gr.sizeof_gr_complex),
                                gr.io_signature(1, 1, gr.sizeof_gr_complex))
        from gnuradio import channels
        r = radio_for(settings.family)
        rate = settings.device_rate
        if not (noise_rms > 0 and noise_lsb > 0):
            raise ValueError("noise_rms = %r, noise_lsb = %r: must be > 0"
                             % (noise_rms, noise_lsb))
        full_scale = noise_rms * (2 ** (r.adc_bits - 1) - 1) / noise_lsb
        interp = int(round(settings.device_rate / in_rate))
        if interp < 1 or abs(interp * in_rate - settings.device_rate) > 1e-6 * rate:
            raise ValueError("in_rate = %.6g S/s: must divide the device rate %.6g S/s "
                             "by an integer" % (in_rate, settings.device_rate))
        self.gain = blocks.multiply_const_cc(1.0)
        self.set_gain(gain_db)
        blocks_in = [self.gain]
        if interp > 1:
            taps = firdes.low_pass(interp, settings.device_rate, 0.5 * in_rate,
                                   0.1 * in_rate, window.WIN_BLACKMAN_HARRIS)
            blocks_in.append(filter.interp_fir_filter_ccc(interp, taps))
        # The beacon lo_offset below the tuned centre, with the receiver's DC leak at the
        # centre and its IQ imbalance (an image of the beacon at +lo_offset).
        w = 2 * math.pi * settings.lo_offset_hz / rate
        if w != 0.0:
            blocks_in.append(blocks.rotator_cc(-w))
        blocks_in.append(blocks.add_const_cc(dc * full_scale))
        blocks_in.append(channels.iqbal_gen(iq_gain_db, iq_phase_deg, 1))
        if r.ddc and w != 0.0:
            # A DDC radio (UHD) shifts the beacon back to 0 Hz in its DSP: the DC leak
            # is then at +lo_offset, the image at +2 lo_offset.
            blocks_in.append(blocks.rotator_cc(w))
        scale = (2 ** (r.adc_bits - 1) - 1) / full_scale
        if clip and r.adc_bits < 16 and r.adc_bits > 8:
            # Saturate I and Q at the converter's full scale (a 16-bit container would
            # hold 2**(16 - bits) times more).
            blocks_in.append(_rail_iq(full_scale))
        if clip and r.adc_bits <= 8:
            blocks_in += [blocks.complex_to_interleaved_char(False, scale),
                          blocks.interleaved_char_to_complex(False, scale)]
        else:
            blocks_in += [blocks.complex_to_interleaved_short(False, scale),
                          blocks.interleaved_short_to_complex(False, False, scale)]
        # rx_rate as the device would tag its stream: the device rate.
        blocks_in.append(rate_retag(rate, interp))
        self.stages = blocks_in
        # The ADC's, in the input's units (without clip: the 16-bit container's).
        self.full_scale = full_scale if clip else 32767.0 / scale
        self.connect(self, *blocks_in, self)

    def set_gain(self, gain_db):
        """The receive gain relative to the one the noise level was set for (dB)."""
        if not (isinstance(gain_db, (int, float)) and math.isfinite(gain_db) and
                -100.0 <= gain_db <= 100.0):
            raise ValueError("sim_radio: gain_db = %r: must be in [-100, 100] dB" % (gain_db,))
        self.gain_db = float(gain_db)
        self.gain.set_k(10.0 ** (self.gain_db / 20.0))


class _commands(gr.basic_block):
    """Message port `command`: a dict's keys of `setters` call them with its values;
    a message that is not such a dict, or a value a setter refuses, is logged, counted
    and dropped."""

    def __init__(self, setters):
        gr.basic_block.__init__(self, name="rfseek_radio_commands", in_sig=None,
                                out_sig=None)
        self.setters, self.dropped = setters, 0
        self.message_port_register_in(pmt.intern("command"))
        self.set_msg_handler(pmt.intern("command"), self.on_command)

    def on_command(self, msg):
        try:
            d = pmt.to_python(msg)
            if not isinstance(d, dict):
                raise ValueError("not a dict")
            calls = [(self.setters[k], float(v)) for k, v in d.items() if k in self.setters]
            if not calls:
                raise ValueError("no key of %s" % sorted(self.setters))
            if not all(math.isfinite(v) for _, v in calls):
                raise ValueError("a value is not a finite number")
        except (AttributeError, TypeError, ValueError) as e:
            self._drop(msg, e)
            return
        for setter, value in calls:
            try:
                setter(value)
            except Exception as e:  # a refused value, a driver's error: the block goes on
                self._drop(msg, e)
                return

    def _drop(self, msg, why):
        self.dropped += 1
        gr.log.warn("radio_source: command %s dropped: %s" % (msg, why))


class _rail_iq(gr.hier_block2):
    """I and Q each held within [-limit, limit], as a pair of converters saturates."""

    def __init__(self, limit):
        gr.hier_block2.__init__(self, "rail_iq", gr.io_signature(1, 1, gr.sizeof_gr_complex),
                                gr.io_signature(1, 1, gr.sizeof_gr_complex))
        from gnuradio import analog
        split, join = blocks.complex_to_float(), blocks.float_to_complex()
        self.connect(self, split)
        for k in (0, 1):
            rail = analog.rail_ff(-limit, limit)
            self.connect((split, k), rail, (join, k))
        self.connect(join, self)


def _hz(f):
    for unit, scale in (("GHz", 1e9), ("MHz", 1e6), ("kHz", 1e3)):
        if abs(f) >= scale:
            return ("%.4f" % (f / scale)).rstrip("0").rstrip(".") + " " + unit
    return "%g Hz" % f


def _sps(f):
    return _hz(f).replace("Hz", "S/s")


def markdown_table(out_rate=100e3):
    """The table as docs/live.md shows it (a test keeps the two equal)."""
    rows = ["| family | radio (driver) | tunes | receive rates | the module's receive "
            "rate, decimation, LO offset | gain (dB) | beacon transmit rate | notes |",
            "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in RADIOS.values():
        s = rx_plan(r.family, 915e6 if r.tunes(915e6) else 2.4e9, out_rate)
        rows.append("| `%s` | %s (%s) | %s-%s | %s; %s | %s, /%d, %s%s | %g-%g | %s | %s |" % (
            r.family, r.label, r.driver, _hz(r.tune_hz[0]), _hz(r.tune_hz[1]),
            " or ".join("%s-%s" % (_sps(lo), _sps(hi)) for lo, hi in r.rx_rates),
            r.rate_rule, _sps(s.device_rate), s.decimation, _hz(s.lo_offset_hz),
            " (by UHD's tune request)" if r.ddc else "", r.gain_db[0], r.gain_db[1],
            _sps(r.tx_rate) if r.tx_rates else "receive only", r.notes))
    return "\n".join(rows) + "\n"
