/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * flight_log: a message sink that keeps what gr::rfseek::channel_source publishes on its
 * "state" port, one entry per slot. A block of a downstream module, written as GNU Radio
 * modules write theirs (public interface, private implementation).
 */
#ifndef INCLUDED_RFSEEK_PROBE_FLIGHT_LOG_H
#define INCLUDED_RFSEEK_PROBE_FLIGHT_LOG_H

#include <gnuradio/block.h>
#include <cstdint>
#include <memory>
#include <vector>

namespace rfseek_probe {

class flight_log : virtual public gr::block
{
public:
    typedef std::shared_ptr<flight_log> sptr;

    //! What one state message said.
    struct entry {
        std::uint64_t slot = 0;
        double x_m = 0.0, y_m = 0.0;
        double distance_m = 0.0;       //!< to the emitter (the simulator's truth)
        double distance_flown_m = 0.0; //!< since the start
        bool arrived = false;
    };

    //! A sink with one message input, "state".
    static sptr make();

    virtual std::vector<entry> entries() const = 0;
    //! State messages that were not a dict with the fields above (logged and dropped).
    virtual std::uint64_t malformed_count() const = 0;
};

} // namespace rfseek_probe

#endif /* INCLUDED_RFSEEK_PROBE_FLIGHT_LOG_H */
