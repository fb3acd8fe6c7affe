/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * Module entry point of gnuradio.rfseek's compiled part (rfseek_python).
 */

#include <pybind11/pybind11.h>

namespace py = pybind11;

void bind_rng(py::module& m);
void bind_scenario(py::module& m);
void bind_world(py::module& m);
void bind_tone_estimator(py::module& m);
void bind_burst_detector(py::module& m);
void bind_tone_detector(py::module& m);
void bind_burst_acquirer(py::module& m);
void bind_channel_source(py::module& m);
void bind_doppler_estimator(py::module& m);
void bind_arrival(py::module& m);
void bind_seeker(py::module& m);
void bind_simulation(py::module& m);
void bind_study(py::module& m);
void bind_seeking_controller(py::module& m);
void bind_mavlink(py::module& m);
void bind_autopilot_session(py::module& m);

PYBIND11_MODULE(rfseek_python, m)
{
    // Base classes of the blocks (gr::sync_block, ...) come from gnuradio.gr.
    py::module::import("gnuradio.gr");

    bind_rng(m);
    bind_scenario(m);
    bind_world(m);
    bind_tone_estimator(m);
    bind_burst_detector(m);
    bind_tone_detector(m);
    bind_burst_acquirer(m);
    bind_channel_source(m);
    bind_doppler_estimator(m);
    bind_arrival(m);
    bind_seeker(m);
    bind_simulation(m);
    bind_study(m);
    bind_seeking_controller(m);
    bind_mavlink(m);
    bind_autopilot_session(m);
}
