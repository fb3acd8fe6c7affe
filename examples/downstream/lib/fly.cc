/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include <gnuradio/top_block.h>
#include <gr-rfseek/channel_source.h>
#include <gr-rfseek/doppler_estimator.h>
#include <gr-rfseek/seeking_controller.h>
#include <gr-rfseek/simulation.h>
#include <rfseek_probe/fly.h>

namespace rfseek_probe {

flight fly(const gr::rfseek::scenario& sc, const std::string& strategy)
{
    namespace rf = gr::rfseek;
    auto tb = gr::make_top_block("rfseek_probe");
    auto source = rf::channel_source::make(sc, "burst", true, false);
    auto estimator =
        rf::doppler_estimator::make(sc.samp_rate_hz, sc.window_len, sc.fft_len);
    auto controller =
        rf::seeking_controller::make(rf::simulation::seeker_for(sc, strategy));
    auto log = flight_log::make();

    tb->connect(source, 0, estimator, 0);
    tb->msg_connect(estimator, "meas", controller, "meas");
    tb->msg_connect(controller, "cmd", source, "cmd");
    tb->msg_connect(source, "state", log, "state");
    tb->run();

    flight f;
    f.log = log->entries();
    f.updates = controller->updates();
    f.malformed = log->malformed_count();
    return f;
}

} // namespace rfseek_probe
