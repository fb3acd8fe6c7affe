/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * fly: one seek through GNU Radio, from the module's blocks (channel_source ->
 * doppler_estimator -> seeking_controller -> channel_source, in lockstep) and this
 * library's flight_log.
 */
#ifndef INCLUDED_RFSEEK_PROBE_FLY_H
#define INCLUDED_RFSEEK_PROBE_FLY_H

#include <gr-rfseek/scenario.h>
#include <rfseek_probe/flight_log.h>
#include <string>
#include <vector>

namespace rfseek_probe {

struct flight {
    std::vector<flight_log::entry> log; //!< every state the source published
    std::uint64_t updates = 0;          //!< heading updates the controller applied
    std::uint64_t malformed = 0;        //!< state messages flight_log dropped
};

//! Fly sc with a seeker strategy ("paper", "adaptive", ...) until the source stops.
flight fly(const gr::rfseek::scenario& sc, const std::string& strategy);

} // namespace rfseek_probe

#endif /* INCLUDED_RFSEEK_PROBE_FLY_H */
