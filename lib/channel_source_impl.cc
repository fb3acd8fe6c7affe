/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * channel_source: streams, tags and messages around a gr::rfseek::world. No physics here.
 */

#include "channel_source_impl.h"
#include <gnuradio/io_signature.h>
#include <boost/date_time/posix_time/posix_time_types.hpp>
#include <boost/thread/thread.hpp>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gr {
namespace rfseek {

namespace {
bool parse_mode(const std::string& mode)
{
    if (mode == "burst")
        return false;
    if (mode == "continuous")
        return true;
    throw std::invalid_argument("channel_source: mode = '" + mode +
                                "': must be 'burst' or 'continuous'");
}
double check_speedup(double speedup)
{
    if (!(speedup > 0.0 && speedup <= 1e6))
        throw std::invalid_argument("speedup: must be in (0, 1e6] (1: real time), got " +
                                    std::to_string(speedup));
    return speedup;
}
// What a controller in the same flowgraph must be told (seeking_controller warns when
// it was told otherwise): the speed the vehicle believes it flies, the carrier and the
// slot period. Fixed with the scenario: made once, carried by every beacon tag.
pmt::pmt_t world_info(const scenario& sc)
{
    pmt::pmt_t w = pmt::make_dict();
    w = pmt::dict_add(
        w, pmt::mp("speed_mps"), pmt::from_double(sc.speed_mps + sc.airspeed_error_mps));
    w = pmt::dict_add(w, pmt::mp("carrier_hz"), pmt::from_double(sc.carrier_hz));
    return pmt::dict_add(w, pmt::mp("slot_period_s"), pmt::from_double(sc.slot_period_s));
}

} // namespace

channel_source::sptr channel_source::make(const scenario& sc,
                                          const std::string& mode,
                                          bool lockstep,
                                          bool realtime,
                                          double speedup,
                                          bool follow_truth)
{
    return gnuradio::make_block_sptr<channel_source_impl>(
        sc, mode, lockstep, realtime, speedup, follow_truth);
}

channel_source_impl::channel_source_impl(const scenario& sc,
                                         const std::string& mode,
                                         bool lockstep,
                                         bool realtime,
                                         double speedup,
                                         bool follow_truth)
    : gr::sync_block("channel_source",
                     gr::io_signature::make(0, 0, 0),
                     gr::io_signature::make(1, 1, sizeof(gr_complex))),
      d_world(sc),
      d_continuous(parse_mode(mode)),
      d_follow(follow_truth),
      d_lockstep(lockstep),
      d_realtime(realtime),
      d_port_cmd(pmt::mp("cmd")),
      d_port_truth(pmt::mp("truth")),
      d_truth_keys{ pmt::mp("time"), pmt::mp("east"),   pmt::mp("north"),
                    pmt::mp("up"),   pmt::mp("v_east"), pmt::mp("v_north"),
                    pmt::mp("v_up"), pmt::mp("heading") },
      d_port_state(pmt::mp("state")),
      d_key_beacon(pmt::mp("rfseek_beacon")),
      d_key_slot(pmt::mp("slot")),
      d_key_time(pmt::mp("time")),
      d_key_heading(pmt::mp("heading")),
      d_key_rx_time(pmt::mp("rx_time")),
      d_key_rx_rate(pmt::mp("rx_rate")),
      d_key_rx_freq(pmt::mp("rx_freq")),
      d_key_world(pmt::mp("world")),
      d_world_info(world_info(sc))
{
    d_speedup = check_speedup(speedup);
    d_cmd_heading = d_world.heading_rad();
    message_port_register_in(d_port_cmd);
    set_msg_handler(d_port_cmd, [this](const pmt::pmt_t& msg) { handle_cmd(msg); });
    message_port_register_in(d_port_truth);
    set_msg_handler(d_port_truth, [this](const pmt::pmt_t& msg) { handle_truth(msg); });
    message_port_register_out(d_port_state);
}

bool channel_source_impl::start()
{
    {
        // The world's present time is due now: a flowgraph started again after a stop
        // goes on at once, not after as long as it had already flown.
        gr::thread::scoped_lock lock(d_setlock);
        reanchor();
    }
    d_logger->debug("start: mode {}, {}, {}, seed {}",
                    mode(),
                    d_follow     ? "following the truth"
                    : d_lockstep ? "lockstep"
                                 : "free-running",
                    d_realtime ? "real time" : "as fast as possible",
                    d_world.config().seed);
    return true;
}

void channel_source_impl::parked(const char* what)
{
    const auto now = std::chrono::steady_clock::now();
    if (!d_parked) {
        d_parked = true;
        d_parked_since = now;
        return;
    }
    if (d_warned_parked ||
        std::chrono::duration<double>(now - d_parked_since).count() < PARKED_WARN_S)
        return;
    d_warned_parked = true;
    const std::string w(what);
    if (w == "cmd")
        d_logger->warn("lockstep: slot {} has been emitted and the world waits for a "
                       "cmd (from a seeking_controller whose cmd port is connected to "
                       "this block's cmd) before it flies on to slot {}; nothing more "
                       "is emitted until one comes. Without a controller, set "
                       "lockstep=False",
                       d_world.slot(),
                       d_world.slot() + 1);
    else
        d_logger->warn("follow_truth: the world waits for the {} on the truth port "
                       "(slot {}: {} truths kept, {} dropped so far); nothing is "
                       "emitted until the simulator's clock passes it",
                       w == "truth" ? "truth past the next slot's time" : "first truth",
                       d_world.slot(),
                       d_truth_count,
                       d_truth_dropped);
}

void channel_source_impl::drop(const std::string& kind, const pmt::pmt_t& msg)
{
    ++d_malformed;
    if (d_logged.insert(kind).second)
        d_logger->warn("cmd dropped ({}): {} (further drops of this kind are counted "
                       "silently; see malformed_count())",
                       kind,
                       pmt::write_string(msg));
}

void channel_source_impl::handle_cmd(const pmt::pmt_t& msg)
{
    gr::thread::scoped_lock lock(d_setlock);
    if (!pmt::is_dict(msg)) {
        drop("not a dict", msg);
        return;
    }
    pmt::pmt_t h, s;
    try {
        h = pmt::dict_ref(msg, d_key_heading, pmt::PMT_NIL);
        s = pmt::dict_ref(msg, d_key_slot, pmt::PMT_NIL);
    } catch (const std::exception&) {
        drop("not a dict", msg);
        return;
    }
    if (!(pmt::is_real(h) || pmt::is_integer(h) || pmt::is_uint64(h))) {
        drop("no numeric 'heading'", msg);
        return;
    }
    // pmt::to_double throws for a uint64 (found by fuzzing): convert it here.
    const double heading =
        pmt::is_uint64(h) ? static_cast<double>(pmt::to_uint64(h)) : pmt::to_double(h);
    if (!std::isfinite(heading)) {
        drop("non-finite 'heading'", msg);
        return;
    }
    if (!pmt::is_null(s) && !d_follow) { // following, the autopilot flies the heading
        if (!(pmt::is_integer(s) || pmt::is_uint64(s))) {
            drop("non-integer 'slot'", msg);
            return;
        }
        const long long k = pmt::is_uint64(s) ? static_cast<long long>(pmt::to_uint64(s))
                                              : pmt::to_long(s);
        const long long now = static_cast<long long>(d_world.slot());
        if (d_lockstep ? k != now : (k > now || k <= d_cmd_slot)) {
            ++d_stale;
            d_logger->debug("cmd for slot {} ignored: current slot is {}{}",
                            k,
                            now,
                            d_lockstep ? ""
                                       : ", newest command applied " +
                                             std::to_string(d_cmd_slot));
            return;
        }
        // Free-running, the receive chain lags the world by a few slots: the newest
        // command is the best the vehicle has, as a real autopilot would fly it.
        if (k < now)
            ++d_late;
        d_cmd_slot = k;
    }
    d_cmd_heading = heading;
    d_have_cmd = true;
    // self_arrival: the controller's `done` ends the run at this slot (located, or
    // given up), as rfseek::simulation does.
    if (d_world.config().self_arrival) {
        pmt::pmt_t done = pmt::PMT_NIL;
        try {
            done = pmt::dict_ref(msg, pmt::mp("done"), pmt::PMT_NIL);
        } catch (const std::exception&) {
        }
        if (pmt::is_bool(done) && pmt::to_bool(done))
            d_end_requested = true;
        if (pmt::is_null(done) && !d_warned_no_done) {
            d_warned_no_done = true;
            d_logger->warn("the scenario has self_arrival but the cmd messages carry no "
                           "'done': the run ends only at the flight cap (give the "
                           "seeking_controller self_arrival too)");
        }
    }
}

void channel_source_impl::handle_truth(const pmt::pmt_t& msg)
{
    gr::thread::scoped_lock lock(d_setlock);
    const auto reject = [&](const std::string& why) {
        ++d_truth_dropped;
        if (d_logged.insert("truth: " + why).second)
            d_logger->warn("truth dropped ({}): {} (further drops of this kind are "
                           "counted silently; see truth_dropped_count())",
                           why,
                           pmt::write_string(msg));
    };
    if (!d_follow) {
        reject("the source does not follow a truth (follow_truth false)");
        return;
    }
    if (!pmt::is_dict(msg) || pmt::is_null(msg)) {
        reject("not a dict");
        return;
    }
    vehicle_truth t;
    double* const fields[TRUTH_FIELDS] = { &t.time_s,   &t.east_m,     &t.north_m,
                                           &t.up_m,     &t.v_east_mps, &t.v_north_mps,
                                           &t.v_up_mps, &t.heading_rad };
    for (std::size_t i = 0; i < TRUTH_FIELDS; ++i) {
        double* const field = fields[i];
        pmt::pmt_t v;
        try {
            v = pmt::dict_ref(msg, d_truth_keys[i], pmt::PMT_NIL);
        } catch (const std::exception&) {
            reject("not a dict");
            return;
        }
        if (pmt::is_real(v) || pmt::is_integer(v))
            *field = pmt::to_double(v);
        else if (pmt::is_uint64(v))
            *field = static_cast<double>(pmt::to_uint64(v));
        else {
            reject("no numeric '" + pmt::symbol_to_string(d_truth_keys[i]) + "'");
            return;
        }
        if (!std::isfinite(*field)) {
            reject("non-finite '" + pmt::symbol_to_string(d_truth_keys[i]) + "'");
            return;
        }
    }
    if (!d_truth.empty() && t.time_s < d_truth.back().time_s) {
        reject("before the last truth");
        return;
    }
    ++d_truth_count;
    d_truth.push_back(t);
}

bool channel_source_impl::truth_at(std::uint64_t k, vehicle_truth& out)
{
    const double t = d_truth_t0 + static_cast<double>(k) * d_world.config().slot_period_s;
    // Keep one truth at or before t (the earlier ones are past for good).
    while (d_truth.size() > 1 && d_truth[1].time_s <= t)
        d_truth.pop_front();
    if (d_truth.empty() || d_truth.back().time_s < t)
        return false; // parked until the simulator's clock has passed t
    const vehicle_truth& a = d_truth.front();
    if (d_truth.size() == 1 || a.time_s >= t) {
        out = a;
        out.time_s = t;
        return true;
    }
    const vehicle_truth& b = d_truth[1];
    const double u = (t - a.time_s) / (b.time_s - a.time_s);
    const auto mix = [u](double p, double q) { return p + u * (q - p); };
    out.time_s = t;
    out.east_m = mix(a.east_m, b.east_m);
    out.north_m = mix(a.north_m, b.north_m);
    out.up_m = mix(a.up_m, b.up_m);
    out.v_east_mps = mix(a.v_east_mps, b.v_east_mps);
    out.v_north_mps = mix(a.v_north_mps, b.v_north_mps);
    out.v_up_mps = mix(a.v_up_mps, b.v_up_mps);
    out.heading_rad = a.heading_rad + u * world::wrap(b.heading_rad - a.heading_rad);
    return true;
}

void channel_source_impl::end_run_now()
{
    d_world.end_run();
    publish_state();
    d_logger->info("the vehicle declared its mission done at slot {}, {:.1f} "
                   "m from the emitter ({} d_v)",
                   d_world.slot(),
                   d_world.distance_m(),
                   d_world.reached() ? "came within" : "never came within");
    d_done = true;
}

void channel_source_impl::publish_state()
{
    const world& w = d_world;
    pmt::pmt_t d = pmt::make_dict();
    d = pmt::dict_add(d, d_key_slot, pmt::from_uint64(w.slot()));
    d = pmt::dict_add(d, d_key_time, pmt::from_double(w.time_s()));
    d = pmt::dict_add(d, pmt::mp("x"), pmt::from_double(w.x_m()));
    d = pmt::dict_add(d, pmt::mp("y"), pmt::from_double(w.y_m()));
    d = pmt::dict_add(d, d_key_heading, pmt::from_double(w.heading_rad()));
    d = pmt::dict_add(
        d, pmt::mp("measured_heading"), pmt::from_double(w.measured_heading_rad()));
    d = pmt::dict_add(d, pmt::mp("distance"), pmt::from_double(w.distance_m()));
    d = pmt::dict_add(
        d, pmt::mp("distance_flown"), pmt::from_double(w.distance_flown_m()));
    d = pmt::dict_add(d, pmt::mp("cfo_hz"), pmt::from_double(w.cfo_hz()));
    d = pmt::dict_add(d, pmt::mp("doppler_hz"), pmt::from_double(w.los_doppler_hz()));
    const double p = std::max(w.received_power(), 1e-300); // one pass over the paths
    d = pmt::dict_add(
        d, pmt::mp("snr_db"), pmt::from_double(10.0 * std::log10(p / w.noise_power())));
    d = pmt::dict_add(d, pmt::mp("power_db"), pmt::from_double(10.0 * std::log10(p)));
    d = pmt::dict_add(d, pmt::mp("arrived"), pmt::from_bool(w.arrived()));
    d = pmt::dict_add(d, pmt::mp("capped"), pmt::from_bool(w.capped()));
    if (w.config().self_arrival) {
        d = pmt::dict_add(d, pmt::mp("reached"), pmt::from_bool(w.reached()));
        d = pmt::dict_add(d, pmt::mp("ended"), pmt::from_bool(w.ended()));
    }
    if (w.slot() == 0) {
        // Scene geometry once, for plots: scatterer positions x0, y0, x1, y1, ...
        std::vector<double> xy;
        for (const auto& s : w.scatterers()) {
            xy.push_back(s.x_m);
            xy.push_back(s.y_m);
        }
        d = pmt::dict_add(d, pmt::mp("scatterers"), pmt::init_f64vector(xy.size(), xy));
    }
    message_port_pub(d_port_state, d);
}

void channel_source_impl::begin_slot(std::uint64_t offset)
{
    const scenario& sc = d_world.config();
    const std::size_t n = d_continuous ? sc.slot_samples() : sc.window_len;
    d_buf.resize(n);
    d_world.synthesize(d_buf.data(), n);
    d_pos = 0;

    const double t = d_world.time_s();
    if (d_world.slot() == 0 || !d_continuous) {
        const double secs = std::floor(t);
        add_item_tag(0,
                     offset,
                     d_key_rx_time,
                     pmt::make_tuple(pmt::from_uint64(static_cast<std::uint64_t>(secs)),
                                     pmt::from_double(t - secs)));
    }
    if (d_world.slot() == 0) {
        add_item_tag(0, offset, d_key_rx_rate, pmt::from_double(sc.samp_rate_hz));
        add_item_tag(0, offset, d_key_rx_freq, pmt::from_double(sc.carrier_hz));
    }
    pmt::pmt_t b = pmt::make_dict();
    b = pmt::dict_add(b, d_key_slot, pmt::from_uint64(d_world.slot()));
    b = pmt::dict_add(b, d_key_time, pmt::from_double(t));
    if (!d_follow) // following, the heading comes from the autopilot (its nav)
        b = pmt::dict_add(
            b, d_key_heading, pmt::from_double(d_world.measured_heading_rad()));
    b = pmt::dict_add(b, d_key_world, d_world_info);
    add_item_tag(0, offset, d_key_beacon, b, alias_pmt());
    publish_state();
}

int channel_source_impl::work(int noutput_items,
                              gr_vector_const_void_star& input_items,
                              gr_vector_void_star& output_items)
{
    auto out = static_cast<gr_complex*>(output_items[0]);
    gr::thread::scoped_lock lock(d_setlock);
    int produced = 0;

    while (produced < noutput_items && !d_done) {
        if (d_started && !d_next_ready && d_pos == d_buf.size()) {
            // Slot fully emitted: fly it, with the cmd for it in lockstep, or follow
            // the truth once the simulator's clock has passed the next slot.
            vehicle_truth next;
            if (d_follow ? !truth_at(d_world.slot() + 1, next)
                         : d_lockstep && !d_have_cmd) {
                parked(d_follow ? "truth" : "cmd");
                break; // parked until the cmd (the truth) for this slot arrives
            }
            d_parked = false;
            d_have_cmd = false;
            if (d_end_requested) {
                end_run_now();
                break;
            }
            if (d_follow)
                d_world.follow(next);
            else
                d_world.advance(d_cmd_heading);
            if (d_world.finished()) {
                publish_state();
                // Under self arrival, arrived() only says "within d_v at this slot":
                // the run ends at the controller's done (ended) or at the cap.
                const bool oracle_arrival =
                    d_world.arrived() && !d_world.config().self_arrival;
                d_logger->info("{} at slot {} after {:.1f} m flown, {:.1f} m from the "
                               "emitter",
                               d_world.ended()  ? "mission done (self arrival)"
                               : oracle_arrival ? "arrived"
                                                : "flight cap reached",
                               d_world.slot(),
                               d_world.distance_flown_m(),
                               d_world.distance_m());
                d_done = true;
                break;
            }
            d_next_ready = true;
        }
        if (!d_started && d_follow) {
            // Slot 0 is the first truth: it places the emitter.
            if (d_truth.empty()) {
                parked("first truth");
                break;
            }
            d_truth_t0 = d_truth.front().time_s;
            if (!d_world.following())
                d_world.follow(d_truth.front());
        }
        if (!d_started || d_next_ready) {
            if (produced > 0 && time_to_due().count() > 0)
                break; // hand over what is ready; the next call waits
            // In short naps, each an interruption point (stop() returns promptly) after
            // which the pace is read again (set_speedup, set_realtime apply at once).
            for (auto left = time_to_due(); left.count() > 0; left = time_to_due()) {
                const auto nap = std::min<long long>(
                    std::chrono::duration_cast<std::chrono::microseconds>(left).count(),
                    MAX_NAP_US);
                lock.unlock();
                boost::this_thread::sleep(boost::posix_time::microseconds(nap));
                lock.lock();
            }
            d_started = true;
            d_next_ready = false;
            begin_slot(nitems_written(0) + produced);
        }
        const std::size_t n =
            std::min<std::size_t>(noutput_items - produced, d_buf.size() - d_pos);
        std::copy_n(d_buf.data() + d_pos, n, out + produced);
        d_pos += n;
        produced += static_cast<int>(n);
    }
    if (produced == 0 && d_done)
        return WORK_DONE;
    return produced;
}

scenario channel_source_impl::config() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_world.config();
}

std::uint64_t channel_source_impl::slot() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_world.slot();
}

std::uint64_t channel_source_impl::malformed_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_malformed;
}

std::uint64_t channel_source_impl::truth_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_truth_count;
}

std::uint64_t channel_source_impl::truth_dropped_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_truth_dropped;
}

std::uint64_t channel_source_impl::stale_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_stale;
}

std::uint64_t channel_source_impl::late_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_late;
}

bool channel_source_impl::lockstep() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_lockstep;
}

bool channel_source_impl::realtime() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_realtime;
}

void channel_source_impl::set_snr_db(double snr_db)
{
    gr::thread::scoped_lock lock(d_setlock);
    d_world.set_snr_db(snr_db);
}

void channel_source_impl::set_heading_noise_rad(double sigma)
{
    gr::thread::scoped_lock lock(d_setlock);
    d_world.set_heading_noise_rad(sigma);
}

void channel_source_impl::set_turn_rate_rad_per_s(double rate)
{
    gr::thread::scoped_lock lock(d_setlock);
    d_world.set_turn_rate_rad_per_s(rate);
}

void channel_source_impl::set_lockstep(bool lockstep)
{
    gr::thread::scoped_lock lock(d_setlock);
    d_lockstep = lockstep;
}

void channel_source_impl::set_realtime(bool realtime)
{
    gr::thread::scoped_lock lock(d_setlock);
    if (realtime && !d_realtime)
        reanchor();
    d_realtime = realtime;
}

double channel_source_impl::speedup() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_speedup;
}

void channel_source_impl::set_speedup(double speedup)
{
    gr::thread::scoped_lock lock(d_setlock);
    d_speedup = check_speedup(speedup);
    reanchor(); // the pace changes from now on, without a jump
}

std::chrono::steady_clock::duration channel_source_impl::paced_time() const
{
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(d_world.time_s() / d_speedup));
}

std::chrono::steady_clock::duration channel_source_impl::time_to_due() const
{
    if (!d_realtime || d_follow) // following: paced by the simulator's clock
        return std::chrono::steady_clock::duration::zero();
    return d_t0 + paced_time() - std::chrono::steady_clock::now();
}

void channel_source_impl::reanchor()
{
    d_t0 = std::chrono::steady_clock::now() - paced_time();
}

} // namespace rfseek
} // namespace gr
