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

from gnuradio import gr

from .flowgraphs import state_to_nav
from .radios import radio_rx_chain, rx_plan, sim_radio


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
    controller; nav_faults: state_to_nav's link faults, e.g. {"delay_s": 0.3})."""

    def __init__(self, sc, family, speedup=1.0, realtime=True, lo_offset=None,
                 device_rate=None, nav_faults=None, **impairments):
        gr.hier_block2.__init__(self, "rehearsal_source", gr.io_signature(0, 0, 0),
                                gr.io_signature(1, 1, gr.sizeof_gr_complex))
        self.settings = rehearsal_plan(sc, family, lo_offset, device_rate)
        self.world = _world(sc, speedup, realtime)
        self.radio = sim_radio(self.settings, sc.samp_rate_hz, _noise_rms(sc),
                               **impairments)
        from .radios import radio_for
        self.chain = radio_rx_chain(self.settings, None, radio_for(family).ddc)
        self.nav = state_to_nav(**(nav_faults or {}))
        self.connect(self.world, self.radio, self.chain, self)
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

    def __init__(self, sc, family, address, speedup=1.0, realtime=True, nav_faults=None,
                 **impairments):
        gr.top_block.__init__(self, "rfseek beacon side")
        from gnuradio import zeromq
        samples, nav, cmd = zmq_ports(address)
        self.settings = rehearsal_plan(sc, family)
        self.world = _world(sc, speedup, realtime)
        self.radio = sim_radio(self.settings, sc.samp_rate_hz, _noise_rms(sc),
                               **impairments)
        self.push = zeromq.push_sink(gr.sizeof_gr_complex, 1, samples, 100, True, -1)
        self.nav = state_to_nav(**(nav_faults or {}))
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
