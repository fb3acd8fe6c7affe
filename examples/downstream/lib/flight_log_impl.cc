/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include <gnuradio/io_signature.h>
#include <rfseek_probe/flight_log.h>
#include <mutex>

namespace rfseek_probe {

namespace {

class flight_log_impl : public flight_log
{
public:
    flight_log_impl()
        : gr::block("flight_log",
                    gr::io_signature::make(0, 0, 0),
                    gr::io_signature::make(0, 0, 0))
    {
        message_port_register_in(pmt::mp("state"));
        set_msg_handler(pmt::mp("state"), [this](const pmt::pmt_t& m) { handle(m); });
    }

    std::vector<entry> entries() const override
    {
        std::lock_guard<std::mutex> lock(d_mutex);
        return d_entries;
    }

    std::uint64_t malformed_count() const override
    {
        std::lock_guard<std::mutex> lock(d_mutex);
        return d_malformed;
    }

private:
    static double number(const pmt::pmt_t& d, const char* key, bool& ok)
    {
        const pmt::pmt_t v = pmt::dict_ref(d, pmt::mp(key), pmt::PMT_NIL);
        ok = ok && pmt::is_number(v);
        return pmt::is_number(v) ? pmt::to_double(v) : 0.0;
    }

    void handle(const pmt::pmt_t& msg)
    {
        std::lock_guard<std::mutex> lock(d_mutex);
        bool ok = pmt::is_dict(msg);
        if (!ok) {
            ++d_malformed;
            return;
        }
        entry e;
        const pmt::pmt_t slot = pmt::dict_ref(msg, pmt::mp("slot"), pmt::PMT_NIL);
        ok = pmt::is_uint64(slot);
        e.slot = ok ? pmt::to_uint64(slot) : 0;
        e.x_m = number(msg, "x", ok);
        e.y_m = number(msg, "y", ok);
        e.distance_m = number(msg, "distance", ok);
        e.distance_flown_m = number(msg, "distance_flown", ok);
        e.arrived = pmt::to_bool(pmt::dict_ref(msg, pmt::mp("arrived"), pmt::PMT_F));
        if (!ok) {
            ++d_malformed;
            return;
        }
        d_entries.push_back(e);
    }

    mutable std::mutex d_mutex;
    std::vector<entry> d_entries;
    std::uint64_t d_malformed = 0;
};

} // namespace

flight_log::sptr flight_log::make()
{
    return gnuradio::make_block_sptr<flight_log_impl>();
}

} // namespace rfseek_probe
