#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Rehearsals of the real receive chain without hardware.

The simulated world's beacon (channel_source, continuous, free-running) is handed over as
a radio of the table would deliver it (sim_radio: the device's rate, LO offset, DC leak,
IQ imbalance, quantisation) to the very chain a radio_source uses (radio_rx_chain), so
that the estimator (alignment "acquire", timing unknown) and the controller see what they
would see live. The vehicle's heading reaches the controller as a vehicle's report would
(on "nav"), not on the beacon's tags.

    rehearsal_source     world + device + receive chain in one process (a drop-in for
                         radio_source with the world's cmd/state/nav ports)
    beacon_side          world + device, its samples and heading reports pushed over
                         ZeroMQ, commands pulled (one process)
    receiver_side        ZeroMQ in -> the receive chain (the other process)

``rfseek-live --source sim --radio FAMILY`` runs the first, ``--zmq-serve ADDR`` /
``--source zmq --zmq ADDR`` the two halves (docs/live.md "Rehearsals").
"""

import math

import numpy
import pmt
from gnuradio import gr

from .flowgraphs import state_to_nav
from .radios import radio_rx_chain, rx_plan, sim_radio


class overflow_injector(gr.basic_block):
    """A receiver's overflows: `lost` samples dropped every `every_s` seconds (the first
    after one period, each at a random point of its period drawn from `seed`), and the
    next sample tagged with its true rx_time (and an rx_rate tag dropped with the
    samples, if any), as UHD does after an "O". rx_time at the
    first sample is 0 (the stream's clock); other tags pass at their new places. Counts:
    overflows, lost_samples."""

    def __init__(self, samp_rate, every_s=10.0, lost=3000, seed=0):
        gr.basic_block.__init__(self, "overflow_injector", [numpy.complex64],
                                [numpy.complex64])
        if not (math.isfinite(samp_rate) and samp_rate > 0):
            raise ValueError("overflow_injector: samp_rate = %r: must be > 0" % samp_rate)
        if not (math.isfinite(every_s) and every_s > 0 and 1 <= lost < every_s * samp_rate):
            raise ValueError("overflow_injector: every_s = %r, lost = %r: every_s must be "
                             "> 0 and lost in [1, every_s x samp_rate)" % (every_s, lost))
        self.set_tag_propagation_policy(gr.TPP_DONT)
        self.rate, self.every = float(samp_rate), int(round(every_s * samp_rate))
        if not int(lost) < self.every:
            raise ValueError("overflow_injector: lost = %r: must be below every_s x "
                             "samp_rate = %d samples" % (lost, self.every))
        self.lost = int(lost)
        self._rng = numpy.random.default_rng(seed)
        self._next = self._draw(1)
        self.overflows = self.lost_samples = 0
        self._tag_time = True  # rx_time due at the next output sample
        self._time, self._rate = pmt.intern("rx_time"), pmt.intern("rx_rate")
        self._held_rate = None

    def _draw(self, k):
        return k * self.every + int(self._rng.integers(0, self.every - self.lost))

    def general_work(self, input_items, output_items):
        x, y = input_items[0], output_items[0]
        n_in, n_out = self.nitems_read(0), self.nitems_written(0)
        if n_in >= self._next:  # inside a drop: consumed, nothing out
            k = min(self._next + self.lost - n_in, len(x))
            for t in self.get_tags_in_window(0, 0, k):  # a rate tag lost in the drop
                if pmt.eq(t.key, self._rate):             # goes out with the next time
                    self._held_rate = t.value
            self.consume(0, k)
            if n_in + k == self._next + self.lost:
                self.overflows += 1
                self.lost_samples += self.lost
                self._next = self._draw(self.overflows + 1)
                self._tag_time = True
            return 0
        k = min(len(x), len(y), self._next - n_in)
        y[:k] = x[:k]
        for t in self.get_tags_in_window(0, 0, k):
            self.add_item_tag(0, n_out + t.offset - n_in, t.key, t.value)
        if self._tag_time and k > 0:
            secs = n_in / self.rate
            self.add_item_tag(0, n_out, self._time, pmt.make_tuple(
                pmt.from_uint64(int(secs)), pmt.from_double(secs - int(secs))))
            if self._held_rate is not None:
                self.add_item_tag(0, n_out, self._rate, self._held_rate)
                self._held_rate = None
            self._tag_time = False
        self.consume(0, k)
        return k


def rehearsal_plan(sc, family, lo_offset=None, device_rate=None):
    """rx_plan for the world `sc` (its carrier, its rate as the estimator's)."""
    if not (hasattr(sc, "carrier_hz") and hasattr(sc, "samp_rate_hz")):
        raise ValueError("sc = %r: must be an rfseek.scenario" % (sc,))
    try:
        return rx_plan(family, sc.carrier_hz, sc.samp_rate_hz, device_rate, lo_offset)
    except ValueError as e:
        raise ValueError("%s (the world's carrier_hz; choose one the radio tunes with "
                         "--set carrier_hz=...)" % e) from None


def _noise_rms(sc):
    from gnuradio import rfseek
    return rfseek.world(sc).noise_power ** 0.5


def _world(sc, speedup, realtime):
    from gnuradio import rfseek
    return rfseek.channel_source(sc, mode="continuous", lockstep=False, realtime=realtime,
                                 speedup=speedup)


class rehearsal_source(gr.hier_block2):
    """The world's beacon through a simulated `family` radio and the receive chain:
    output at the world's rate (with rx_rate), message ports cmd (in; to the world),
    state (out; the world's truth, for logs) and nav (out; heading reports for the
    controller). faults: (kind, arguments) pairs, as rfseek-live --fault gives them:
    ("nav", state_to_nav's link faults), ("overflow", overflow_injector's), ("adc",
    sim_radio's clip=False: a converter that does not saturate, a study's reference)."""

    def __init__(self, sc, family, speedup=1.0, realtime=True, lo_offset=None,
                 device_rate=None, faults=None, **impairments):
        gr.hier_block2.__init__(self, "rehearsal_source", gr.io_signature(0, 0, 0),
                                gr.io_signature(1, 1, gr.sizeof_gr_complex))
        self.settings = rehearsal_plan(sc, family, lo_offset, device_rate)
        self.world = _world(sc, speedup, realtime)
        faults = dict(faults or [])
        self.radio = sim_radio(self.settings, sc.samp_rate_hz, _noise_rms(sc),
                               **dict(impairments, **faults.get("adc", {})))
        from .radios import radio_for
        self.chain = radio_rx_chain(self.settings, None, radio_for(family).ddc)
        self.nav = state_to_nav(**faults.get("nav", {}))
        stages = [self.world, self.radio, self.chain]
        if "overflow" in faults:  # (at the estimator's rate: the tags' places are exact)
            self.overflow = overflow_injector(self.chain.out_rate(), seed=sc.seed,
                                              **faults["overflow"])
            stages.append(self.overflow)
        self.connect(*stages, self)
        for port in ("cmd",):
            self.message_port_register_hier_in(port)
            self.msg_connect(self, port, self.world, port)
        for port in ("state", "nav"):
            self.message_port_register_hier_out(port)
        self.msg_connect(self.world, "state", self, "state")
        self.msg_connect(self.world, "state", self.nav, "state")
        self.msg_connect(self.nav, "nav", self, "nav")

    def out_rate(self):
        return self.chain.out_rate()

    def band(self):
        return self.settings.band_hz

    def full_scale(self):
        """The simulated radio's ADC full scale in the output's units."""
        return self.radio.full_scale

    def late_count(self):
        return self.world.late_count()

    def stale_count(self):
        return self.world.stale_count()

    def slot(self):
        """The simulated world's current slot."""
        return self.world.slot()


def zmq_ports(address):
    """tcp://HOST:PORT -> the three addresses: samples (PORT), heading reports (PORT+1),
    commands (PORT+2)."""
    head, _, port = address.rpartition(":")
    if not head.startswith("tcp://") or not port.isdigit() or not 0 < int(port) < 65534:
        raise ValueError("zmq address = %r: must be tcp://HOST:PORT (PORT and the next two "
                         "are used)" % address)
    p = int(port)
    return tuple("%s:%d" % (head, p + k) for k in range(3))


class beacon_side(gr.top_block):
    """One process: the world's beacon through a simulated `family` radio, pushed over
    ZeroMQ (samples with their tags at `address`, heading reports at the next port), the
    controller's commands pulled from the port after. Ends when the world does."""

    def __init__(self, sc, family, address, speedup=1.0, realtime=True, faults=None,
                 **impairments):
        gr.top_block.__init__(self, "rfseek beacon side")
        from gnuradio import zeromq
        samples, nav, cmd = zmq_ports(address)
        self.settings = rehearsal_plan(sc, family)
        self.world = _world(sc, speedup, realtime)
        faults = dict(faults or [])
        self.radio = sim_radio(self.settings, sc.samp_rate_hz, _noise_rms(sc),
                               **dict(impairments, **faults.get("adc", {})))
        self.push = zeromq.push_sink(gr.sizeof_gr_complex, 1, samples, 100, True, -1)
        if "overflow" in faults:
            raise ValueError("--fault overflow: in a one-process rehearsal (--source sim "
                             "--radio FAMILY), not served over ZeroMQ")
        self.nav = state_to_nav(**faults.get("nav", {}))
        self.nav_out = zeromq.push_msg_sink(nav, 100, True)
        self.cmd_in = zeromq.pull_msg_source(cmd, 100, True)
        self.connect(self.world, self.radio, self.push)
        self.msg_connect(self.world, "state", self.nav, "state")
        self.msg_connect(self.nav, "nav", self.nav_out, "in")
        self.msg_connect(self.cmd_in, "out", self.world, "cmd")


class receiver_side(gr.hier_block2):
    """The other process's source: samples pulled from ZeroMQ at `address` through the
    receive chain of `family` (the beacon at `freq`, estimator rate `out_rate`); message
    ports nav (out; the vehicle's heading reports) and cmd (in; pushed to the beacon
    side)."""

    def __init__(self, family, freq, address, out_rate=100e3):
        gr.hier_block2.__init__(self, "receiver_side", gr.io_signature(0, 0, 0),
                                gr.io_signature(1, 1, gr.sizeof_gr_complex))
        from gnuradio import zeromq
        from .radios import radio_for
        samples, nav, cmd = zmq_ports(address)
        self.settings = rx_plan(family, freq, out_rate)
        self.pull = zeromq.pull_source(gr.sizeof_gr_complex, 1, samples, 100, True, -1)
        self.chain = radio_rx_chain(self.settings, None, radio_for(family).ddc)
        self.nav_in = zeromq.pull_msg_source(nav, 100, False)
        self.cmd_out = zeromq.push_msg_sink(cmd, 100, False)
        self.connect(self.pull, self.chain, self)
        self.message_port_register_hier_in("cmd")
        self.message_port_register_hier_out("nav")
        self.msg_connect(self, "cmd", self.cmd_out, "in")
        self.msg_connect(self.nav_in, "out", self, "nav")

    def out_rate(self):
        return self.chain.out_rate()

    def band(self):
        return self.settings.band_hz
