/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * seeking_controller: message parsing and publishing around a gr::rfseek::seeker. No
 * control logic here.
 */

#include "seeking_controller_impl.h"
#include <gnuradio/io_signature.h>
#include <algorithm>
#include <cmath>

namespace gr {
namespace rfseek {

namespace {
bool number(const pmt::pmt_t& v)
{
    return pmt::is_real(v) || pmt::is_integer(v) || pmt::is_uint64(v);
}

// A number() as a double. pmt::to_double throws for a uint64 (found by fuzzing: a uint64
// heading or frequency was an exception out of the message handler).
double as_double(const pmt::pmt_t& v)
{
    return pmt::is_uint64(v) ? static_cast<double>(pmt::to_uint64(v)) : pmt::to_double(v);
}
} // namespace

seeking_controller::sptr seeking_controller::make(const seeker_config& cfg)
{
    return gnuradio::make_block_sptr<seeking_controller_impl>(cfg);
}

seeking_controller_impl::seeking_controller_impl(const seeker_config& cfg)
    : gr::block("seeking_controller",
                gr::io_signature::make(0, 0, 0),
                gr::io_signature::make(0, 0, 0)),
      d_seeker(seeker::make(cfg)),
      d_port_meas(pmt::mp("meas")),
      d_port_nav(pmt::mp("nav")),
      d_port_cmd(pmt::mp("cmd")),
      d_port_telemetry(pmt::mp("telemetry")),
      d_port_status(pmt::mp("status")),
      d_key_slot(pmt::mp("slot")),
      d_key_heading(pmt::mp("heading")),
      d_key_freq(pmt::mp("freq_hz")),
      d_key_valid(pmt::mp("valid")),
      d_key_snr(pmt::mp("snr_db")),
      d_key_power(pmt::mp("power_db")),
      d_key_time(pmt::mp("time")),
      d_key_stage(pmt::mp("stage"))
{
    message_port_register_in(d_port_meas);
    message_port_register_in(d_port_nav);
    message_port_register_out(d_port_cmd);
    message_port_register_out(d_port_telemetry);
    message_port_register_out(d_port_status);
    set_msg_handler(d_port_meas, [this](const pmt::pmt_t& m) { handle_meas(m); });
    set_msg_handler(d_port_nav, [this](const pmt::pmt_t& m) { handle_nav(m); });
}

void seeking_controller_impl::drop(const std::string& port,
                                   const std::string& kind,
                                   const pmt::pmt_t& msg)
{
    ++d_malformed;
    if (d_logged.insert(port + ":" + kind).second)
        d_logger->warn(
            "{} message dropped ({}): {} (further drops of this kind are counted "
            "silently; see malformed_count())",
            port,
            kind,
            pmt::write_string(msg));
}

void seeking_controller_impl::handle_nav(const pmt::pmt_t& msg)
{
    gr::thread::scoped_lock lock(d_setlock);
    if (!pmt::is_dict(msg) || pmt::is_null(msg)) {
        drop("nav", "not a dict", msg);
        return;
    }
    pmt::pmt_t h;
    try {
        h = pmt::dict_ref(msg, d_key_heading, pmt::PMT_NIL);
    } catch (const std::exception&) {
        drop("nav", "not a dict", msg);
        return;
    }
    if (!number(h) || !std::isfinite(as_double(h))) {
        drop("nav", "no finite 'heading'", msg);
        return;
    }
    // Its own time, when it has one (out-of-order and late reports go where they
    // belong).
    pmt::pmt_t t = pmt::PMT_NIL;
    try {
        t = pmt::dict_ref(msg, d_key_time, pmt::PMT_NIL);
    } catch (const std::exception&) {
    }
    const bool timed = number(t) && std::isfinite(as_double(t));
    const bool was_foreign = d_nav.foreign_clock();
    d_nav.report(as_double(h), timed, timed ? as_double(t) : 0.0);
    if (d_nav.foreign_clock() && !was_foreign)
        d_logger->info(
            "nav reports' 'time' is not the measurements' clock (5 reports in a "
            "row over 5 s from the latest window): their offset is learned from "
            "the fastest reports");
    drain();
}

void seeking_controller_impl::check_world(const pmt::pmt_t& world)
{
    d_world_checked = true;
    const seeker_config& c = d_seeker->config();
    const struct {
        const char* key;
        double told;
        const char* unit;
    } fields[] = { { "speed_mps", c.speed_mps, "m/s" },
                   { "carrier_hz", c.carrier_hz, "Hz" },
                   { "slot_period_s", c.slot_period_s, "s" } };
    for (const auto& f : fields) {
        const pmt::pmt_t v = pmt::dict_ref(world, pmt::mp(f.key), pmt::PMT_NIL);
        if (!number(v))
            continue;
        const double world_value = as_double(v);
        if (!std::isfinite(world_value) ||
            std::abs(world_value - f.told) <= 1e-6 * std::abs(world_value))
            continue;
        d_logger->warn("{}: the world in this flowgraph (channel_source) has {:g} {} but "
                       "this controller was told {:g} {}; the seek is steered by what "
                       "the controller was told. Set both from one variable",
                       f.key,
                       world_value,
                       f.unit,
                       f.told,
                       f.unit);
    }
}

void seeking_controller_impl::handle_meas(const pmt::pmt_t& msg)
{
    gr::thread::scoped_lock lock(d_setlock);
    if (!pmt::is_dict(msg) || pmt::is_null(msg)) {
        drop("meas", "not a dict", msg);
        return;
    }
    pmt::pmt_t slot, freq, valid, heading, snr, power, time;
    try {
        slot = pmt::dict_ref(msg, d_key_slot, pmt::PMT_NIL);
        freq = pmt::dict_ref(msg, d_key_freq, pmt::PMT_NIL);
        valid = pmt::dict_ref(msg, d_key_valid, pmt::PMT_NIL);
        heading = pmt::dict_ref(msg, d_key_heading, pmt::PMT_NIL);
        snr = pmt::dict_ref(msg, d_key_snr, pmt::PMT_NIL);
        power = pmt::dict_ref(msg, d_key_power, pmt::PMT_NIL);
        time = pmt::dict_ref(msg, d_key_time, pmt::PMT_NIL);
    } catch (const std::exception&) {
        drop("meas", "not a dict", msg);
        return;
    }
    if (!(pmt::is_uint64(slot) || (pmt::is_integer(slot) && pmt::to_long(slot) >= 0))) {
        drop("meas", "no non-negative integer 'slot'", msg);
        return;
    }
    if (!d_world_checked) {
        const pmt::pmt_t w = pmt::dict_ref(msg, pmt::mp("world"), pmt::PMT_NIL);
        if (pmt::is_dict(w) && !pmt::is_null(w))
            check_world(w);
    }
    measurement m;
    m.slot = pmt::is_uint64(slot) ? pmt::to_uint64(slot)
                                  : static_cast<std::uint64_t>(pmt::to_long(slot));
    // A measurement whose fields are unusable is answered as an invalid one, so a
    // lockstep loop keeps going; it is still counted and logged as malformed.
    bool ok = number(freq) && pmt::is_bool(valid);
    if (!ok)
        drop("meas", "no numeric 'freq_hz' or boolean 'valid'", msg);
    m.freq_hz = ok ? as_double(freq) : 0.0;
    m.valid = ok && pmt::to_bool(valid) && std::isfinite(m.freq_hz);
    if (!std::isfinite(m.freq_hz))
        m.freq_hz = 0.0;
    // A NaN or infinite snr_db, power_db or time cannot be trusted, nor the frequency
    // measured with it: answered as an invalid measurement, and never passed on.
    for (const auto& [v, field] : { std::make_pair(snr, &m.snr_db),
                                    std::make_pair(power, &m.power_db),
                                    std::make_pair(time, &m.time_s) }) {
        if (!number(v))
            continue;
        const double x = as_double(v);
        if (std::isfinite(x))
            *field = x;
        else
            m.valid = false;
    }
    // Without a time, the slot's nominal one (the arrival detector and the locator
    // measure time; the estimator always sends it).
    if (!number(time))
        m.time_s = static_cast<double>(m.slot) * d_seeker->config().slot_period_s;
    d_nav.measured(m.time_s);
    ++d_meas;
    if (number(heading) && std::isfinite(as_double(heading))) {
        m.has_heading = true;
        m.heading_rad = as_double(heading);
    }
    // A window whose heading comes on nav waits (in order) for the report of its time:
    // a late link's reports come after the window is measured.
    d_pending.push_back(m);
    d_pending_since.push_back(std::chrono::steady_clock::now());
    drain();
}

bool seeking_controller_impl::start()
{
    if (d_watchdog.joinable()) { // (started twice without a stop)
        d_running = false;
        d_watchdog.join();
    }
    d_running = true;
    d_watchdog = std::thread([this] {
        while (d_running) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            gr::thread::scoped_lock lock(d_setlock);
            drain(true);
        }
    });
    return block::start();
}

bool seeking_controller_impl::stop()
{
    d_running = false;
    if (d_watchdog.joinable())
        d_watchdog.join();
    gr::thread::scoped_lock lock(d_setlock);
    drain(true, true); // (what waits is answered at once, not lost)
    return block::stop();
}

void seeking_controller_impl::drain(bool watchdog, bool force)
{
    const double half_slot = 0.5 * d_seeker->config().slot_period_s;
    while (!d_pending.empty()) {
        const measurement& m = d_pending.front();
        // (Reports without a time of their own are timed by their arrival: nothing to
        // wait for.)
        const bool ready =
            m.has_heading || !d_nav.any() || !d_nav.timed() || !std::isfinite(m.time_s) ||
            d_nav.newest() >= m.time_s - half_slot ||
            d_nav.latest_measured() - m.time_s >= d_nav_wait_s || d_pending.size() > 256;
        // Waited 0.5 s of host time (a lockstep source waits for the cmd, or the link is
        // slower than the world): answered with the reports there are.
        const bool overdue = force || (watchdog && std::chrono::steady_clock::now() -
                                                           d_pending_since.front() >
                                                       std::chrono::milliseconds(500));
        if (!ready && !overdue)
            return;
        if (overdue && !ready && !d_logged_wait) {
            d_logged_wait = true;
            d_logger->info("a window waited 0.5 s for the nav report of its time (a "
                           "lockstep source, or a link slower than the world): answered "
                           "with the reports there are");
        }
        const measurement next = m;
        d_pending.pop_front();
        d_pending_since.pop_front();
        process(next);
    }
}

void seeking_controller_impl::process(measurement m)
{
    bool from_nav = false;
    nav_history::pick nav;
    if (!m.has_heading && d_nav.any()) {
        // The report nearest the window's time; none within a second: the strategy
        // flies on its own heading model, and the telemetry says so.
        nav = d_nav.at(m.time_s);
        from_nav = true;
        if (nav.found) {
            m.has_heading = true;
            m.heading_rad = nav.heading_rad;
        } else if (d_unpaired++ == 0) {
            d_logger->warn("no heading report within {:g} s of the window at {:.3f} s: "
                           "measured without the vehicle's heading (counted: "
                           "unpaired_count())",
                           d_nav.max_gap_s(),
                           m.time_s);
        }
    }
    if (!d_seeking && !m.has_heading && d_wait_heading) {
        // No heading yet: the strategy would start from an assumed one (a straight
        // line away from the emitter if it is wrong). The vehicle keeps its course.
        if (d_waiting++ == 0)
            d_logger->info("waiting for the vehicle's first heading (a 'heading' in meas "
                           "or a nav report) before seeking; measurements until then "
                           "are counted (waiting_count()) and get no cmd");
        return;
    }
    if (!d_seeking && d_waiting > 0)
        d_logger->info("first heading after {} measurements: seeking", d_waiting);
    // Once the strategy has started, waiting no longer applies (a later switch to
    // waiting must not stop a flight).
    d_seeking = true;
    if (!m.valid)
        ++d_invalid;

    const command c = d_seeker->update(m);

    pmt::pmt_t cmd = pmt::make_dict();
    cmd = pmt::dict_add(cmd, d_key_slot, pmt::from_uint64(c.slot));
    cmd = pmt::dict_add(cmd, d_key_heading, pmt::from_double(c.heading_rad));
    cmd = pmt::dict_add(cmd, d_key_stage, pmt::from_long(c.stage));
    if (d_seeker->config().self_arrival) {
        cmd = pmt::dict_add(cmd, pmt::mp("status"), pmt::from_long(c.status));
        cmd = pmt::dict_add(cmd, pmt::mp("done"), pmt::from_bool(c.done));
    }
    // The status and the telemetry go out before the cmd: a cmd that says `done` ends
    // a simulated flight (channel_source stops), and what is published after it can be
    // lost with the flowgraph's end (the last "located" was, under a slow sanitizer).
    publish_status(c, m.time_s);
    publish_telemetry(c, m, from_nav, nav);
    message_port_pub(d_port_cmd, cmd);
}

void seeking_controller_impl::publish_telemetry(const command& c,
                                                const measurement& m,
                                                bool from_nav,
                                                const nav_history::pick& nav)
{
    pmt::pmt_t t = pmt::make_dict();
    t = pmt::dict_add(t, d_key_slot, pmt::from_uint64(c.slot));
    t = pmt::dict_add(t, d_key_time, pmt::from_double(m.time_s));
    t = pmt::dict_add(t, d_key_stage, pmt::from_long(c.stage));
    t = pmt::dict_add(t, pmt::mp("theta_est"), pmt::from_double(c.theta_est_rad));
    t = pmt::dict_add(t, d_key_heading, pmt::from_double(c.heading_rad));
    // The vehicle's heading this window was paired with (the meas's or the last nav;
    // absent when there is none).
    if (m.has_heading)
        t = pmt::dict_add(t, pmt::mp("flown_heading"), pmt::from_double(m.heading_rad));
    // From a nav report: how far its time was from the window's; none near: paired
    // false.
    if (from_nav) {
        t = pmt::dict_add(t, pmt::mp("nav_paired"), pmt::from_bool(nav.found));
        if (nav.found)
            t = pmt::dict_add(t, pmt::mp("nav_offset_s"), pmt::from_double(nav.offset_s));
    }
    t = pmt::dict_add(t, pmt::mp("update"), pmt::from_bool(c.update));
    t = pmt::dict_add(t, pmt::mp("holding"), pmt::from_bool(c.holding));
    t = pmt::dict_add(t, pmt::mp("accepted"), pmt::from_bool(c.accepted));
    t = pmt::dict_add(
        t, pmt::mp("filtered_freq_hz"), pmt::from_double(c.filtered_freq_hz));
    t = pmt::dict_add(t, d_key_freq, pmt::from_double(m.valid ? m.freq_hz : 0.0));
    t = pmt::dict_add(t, d_key_valid, pmt::from_bool(m.valid));
    t = pmt::dict_add(t, pmt::mp("status"), pmt::from_long(c.status));
    message_port_pub(d_port_telemetry, t);
}

void seeking_controller_impl::publish_status(const command& c, double time_s)
{
    // On every change of status, and on every new fix while located.
    const bool new_fix =
        c.status == 2 && c.location.valid && c.location.time_s != d_fix_time;
    if (c.status == d_status && c.done == d_done && !new_fix)
        return;
    d_status = c.status;
    d_done = c.done;
    if (new_fix)
        d_location = c.location;
    static const char* names[] = { "seeking", "arrived", "located" };
    pmt::pmt_t s = pmt::make_dict();
    s = pmt::dict_add(s, pmt::mp("status"), pmt::mp(names[std::clamp(c.status, 0, 2)]));
    s = pmt::dict_add(s, d_key_slot, pmt::from_uint64(c.slot));
    s = pmt::dict_add(s, d_key_time, pmt::from_double(time_s));
    s = pmt::dict_add(s, pmt::mp("done"), pmt::from_bool(c.done));
    if (new_fix) {
        d_fix_time = c.location.time_s;
        const emitter_location& l = c.location;
        auto add = [&s](const char* k, double v) {
            s = pmt::dict_add(
                s, pmt::mp(k), pmt::from_double(std::isfinite(v) ? v : 0.0));
        };
        add("east_m", l.east_m);
        add("north_m", l.north_m);
        add("range_m", std::hypot(l.east_m, l.north_m));
        add("bearing_rad", std::atan2(l.north_m, l.east_m));
        add("dr_x_m", l.dr_x_m);
        add("dr_y_m", l.dr_y_m);
        add("major_m", l.major_m);
        add("minor_m", l.minor_m);
        add("major_angle_rad", l.major_angle_rad);
        add("wind_east_mps", l.wind_east_mps);
        add("wind_north_mps", l.wind_north_mps);
        add("altitude_m", l.altitude_m);
        add("fix_time", l.time_s);
        add("rms_hz", l.rms_hz);
        add("consistency", l.consistency);
        add("major50_m", l.major50_m);
        add("minor50_m", l.minor50_m);
        s = pmt::dict_add(s, pmt::mp("unsure"), pmt::from_bool(l.unsure));
        s = pmt::dict_add(s, pmt::mp("wandered"), pmt::from_bool(l.wandered));
    }
    message_port_pub(d_port_status, s);
}

seeker_config seeking_controller_impl::config() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_seeker->config();
}

int seeking_controller_impl::stage() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_seeker->stage();
}

double seeking_controller_impl::theta_est() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_seeker->theta_est_rad();
}

std::uint64_t seeking_controller_impl::updates() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_seeker->updates();
}

std::uint64_t seeking_controller_impl::meas_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_meas;
}

std::uint64_t seeking_controller_impl::invalid_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_invalid;
}

std::uint64_t seeking_controller_impl::malformed_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_malformed;
}

void seeking_controller_impl::set_wait_for_heading(bool wait)
{
    gr::thread::scoped_lock lock(d_setlock);
    d_wait_heading = wait;
}

bool seeking_controller_impl::set_wind_forecast(double east_mps, double north_mps)
{
    gr::thread::scoped_lock lock(d_setlock);
    seeker_config c = d_seeker->config();
    c.wind_forecast_east_mps = east_mps;
    c.wind_forecast_north_mps = north_mps;
    // A callback in a running flight (a GUI slider) must not stop the controller: a
    // bad value is logged and the forecast in use kept.
    try {
        c.validate();
    } catch (const std::invalid_argument& e) {
        d_logger->error("set_wind_forecast: {}; the forecast in use is kept", e.what());
        return false;
    }
    if (d_seeker->set_wind_forecast(east_mps, north_mps))
        return true;
    if ((east_mps != 0.0 || north_mps != 0.0) && d_logged.insert("wind_forecast").second)
        d_logger->warn("set_wind_forecast: strategy {} flies no ground track here: the "
                       "forecast is not used",
                       c.strategy);
    return false;
}

bool seeking_controller_impl::wait_for_heading() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_wait_heading;
}

std::uint64_t seeking_controller_impl::unpaired_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_unpaired;
}

std::uint64_t seeking_controller_impl::waiting_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_waiting;
}

} // namespace rfseek
} // namespace gr

namespace gr {
namespace rfseek {

bool seeking_controller_impl::done() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_done;
}

int seeking_controller_impl::status() const
{
    gr::thread::scoped_lock lock(setlock());
    return std::max(d_status, 0);
}

emitter_location seeking_controller_impl::location() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_location;
}

} // namespace rfseek
} // namespace gr
