/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * homing_seeker: any strategy, plus what a vehicle without GPS decides by itself near
 * the emitter (seeker_config::self_arrival, docs/seeker.md "Arrival and location"):
 *   seeking   the strategy steers; the overflight detector watches its measurements.
 *             Once it fires (stage 3, still seeking): orbit to the left at v /
 *             loiter_radius_m, dead-reckon the path (measured heading x airspeed) and
 *             collect the frequencies; after locate_orbits orbits the emitter_locator
 *             fits the emitter; fly to the estimate, orbit it (wind triangle) and fit
 *             again after the transit plus locate_orbits orbits; each fit is the next
 *             estimate orbited;
 *   arrived   a fit agrees within arrival_confirm_m with the estimate orbited and lies
 *             by the vehicle, and no plane wave explains the data nearly as well
 *             (arrival_confirm_m = 0: arrived when the detector fires);
 *   located   a fix with a 95 % ellipse under locate_max_axis_m is published (the slot
 *             after arrived at the earliest) and `done` set. The orbit goes on around
 *             the last estimate; no more fits after `done`.
 *   Without a fix after locate_max_orbits (extended by each move of the estimate, six
 *   at most, and by the arrival): back to seeking (locate_retry), or `done` without a
 *   location; unless a confirming fit was held back only by its honest ellipse (wider
 *   than 600 m) and the orbits around the estimate swing as they do over the emitter:
 *   arrived, and that fix published as unsure.
 */

#include "angle.h"
#include "arrival_math.h"
#include "heading_filter.h"
#include "strategies.h"
#include <gr-rfseek/arrival.h>
#include <gr-rfseek/scenario.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>

namespace gr {
namespace rfseek {

namespace {

overflight_config detector_config(const seeker_config& c)
{
    overflight_config o;
    o.max_doppler_hz = c.max_doppler_hz();
    o.slot_period_s = c.slot_period_s;
    o.swing = c.arrival_swing;
    o.window_s = c.arrival_window_s;
    o.heading_band_rad = c.arrival_heading_band_rad;
    o.power_rise_db = c.arrival_power_rise_db;
    o.near_swing = c.arrival_near_swing;
    o.near_power_db = c.arrival_near_power_db;
    o.block_slots = c.arrival_block_slots;
    o.confirm_blocks = c.arrival_confirm_blocks;
    o.min_snr_db = c.min_snr_db;
    o.encircle_amplitude = c.arrival_encircle;
    return o;
}

class homing_seeker : public seeker
{
public:
    homing_seeker(const seeker_config& cfg, std::unique_ptr<seeker> strategy)
        : d_cfg(cfg),
          d_inner(std::move(strategy)),
          d_detector(detector_config(cfg)),
          d_locator(SPEED_OF_LIGHT / cfg.carrier_hz,
                    SEARCH_RADIUS_M,
                    cfg.locate_gust_mps,
                    cfg.locate_gust_tau_s,
                    std::isnan(cfg.locate_altitude_m) ? 0.0 : cfg.locate_altitude_m,
                    std::isnan(cfg.locate_altitude_m) ? 0.0
                                                      : cfg.locate_altitude_sigma_m),
          d_heading_filter(cfg.loiter_heading_gain),
          d_next_fit_s(cfg.locate_orbits * 2.0 * M_PI * cfg.loiter_radius_m /
                       cfg.speed_mps)
    {
        locator_nuisance nu;
        nu.altimeter_m = cfg.locate_altimeter_range_m;
        nu.airspeed_mps = cfg.speed_mps;
        nu.scale95 = cfg.locate_scale95;
        nu.scale50 = cfg.locate_scale50;
        d_locator.set_nuisance(nu);
    }

    command update(const measurement& m) override
    {
        if (!d_loitering) {
            command c = d_inner->update(m);
            d_heading_cmd = c.heading_rad;
            const double h = m.has_heading ? m.heading_rad : c.heading_rad;
            if (d_detector.update(
                    m.time_s, m.freq_hz, m.power_db, m.snr_db, m.valid, h)) {
                d_loitering = true;
                if (d_cfg.arrival_confirm_m <= 0.0)
                    d_status = 1; // declared on the overflight alone
                d_loiter_start = m.time_s;
                d_deadline_s = d_cfg.locate_max_orbits * orbit_s();
                d_retargets = 0;
                d_last_slot = m.slot;
                d_last_heading = h;
                d_heading_filter.reset(h);
                d_read_slot = m.slot;
                d_heading_cmd = h; // the orbit starts from the heading flown
                c.heading_rad = wrap_remainder(d_heading_cmd + turn_per_slot());
                d_heading_cmd = c.heading_rad;
                c.stage = 3;
            }
            c.status = d_status;
            return c;
        }
        return loiter(m);
    }

    const seeker_config& config() const override { return d_cfg; }
    bool set_wind_forecast(double east_mps, double north_mps) override
    {
        if (!d_inner->set_wind_forecast(east_mps, north_mps))
            return false;
        d_cfg.wind_forecast_east_mps = east_mps;
        d_cfg.wind_forecast_north_mps = north_mps;
        return true;
    }
    int stage() const override { return d_loitering ? 3 : d_inner->stage(); }
    double theta_est_rad() const override
    {
        if (d_location.valid) // toward the fix, from where the vehicle is now
            return std::atan2(d_location.north_m + d_location.dr_y_m - d_y,
                              d_location.east_m + d_location.dr_x_m - d_x);
        if (d_centred) // toward the estimate being orbited
            return std::atan2(d_target_y - d_y, d_target_x - d_x);
        return d_inner->theta_est_rad();
    }
    std::uint64_t updates() const override { return d_inner->updates(); }

private:
    double turn_per_slot() const
    {
        return d_cfg.speed_mps / d_cfg.loiter_radius_m * d_cfg.slot_period_s;
    }
    double orbit_s() const
    {
        return 2.0 * M_PI * d_cfg.loiter_radius_m / d_cfg.speed_mps;
    }

    /*
     * Whether the first orbit is checked (arrival_far_amplitude): only when the vehicle
     * flies at least MIN_FAR_CHECK_ALTITUDE_M up (locate_altitude_m). Near the emitter
     * the line of sight is then steep and an orbit's Doppler swings much less than far
     * away (0.7 f_d,max 100 m off at 100 m height); in a flat world an orbit 50 m off
     * already swings by 0.94 f_d,max and nothing tells it from one 5 km out.
     */
    bool far_check() const
    {
        return d_cfg.arrival_far_amplitude > 0.0 &&
               d_cfg.locate_altitude_m >= MIN_FAR_CHECK_ALTITUDE_M;
    }

    // The first orbit's Doppler amplitude (Hz) from which the emitter is far
    // (seeker_config::far_amplitude: raised for wide orbits).
    double far_amplitude_hz() const
    {
        return d_cfg.far_amplitude() * d_cfg.max_doppler_hz();
    }

    /*
     * Whether the orbits flown around the estimate (the last CENTRED_ORBITS of them, up
     * to MAX_ORBITS until their headings go all round) place the emitter near: their
     * Doppler's amplitude in the heading (doppler_amplitude) stays below
     * NEAR_AMPLITUDE_FRACTION of the far check's. Far from the emitter every path arrives
     * from one bearing and a turn swings the Doppler by f_d,max wherever the orbit is
     * (gusts moved it to 0.80-1.11 over orbits 1.6-5 km off); on an orbit around the
     * emitter the ground velocity stays across the line of sight and the Doppler barely
     * swings (`windy`: median 0.4 f_d,max, 90 % under 0.69). Only where the far check
     * runs (at least MIN_FAR_CHECK_ALTITUDE_M up): lower, an orbit 50 m off swings as far
     * as one far.
     */
    bool orbits_place_emitter_near() const
    {
        if (!far_check())
            return false;
        const double amp =
            recent_amplitude(d_centred_orbits, orbit_s(), CENTRED_ORBITS, MAX_ORBITS);
        return std::isfinite(amp) && amp < NEAR_AMPLITUDE_FRACTION * far_amplitude_hz();
    }

    // Back to seeking: the strategy resumes where it was; the detector starts anew.
    command resume_seeking(const measurement& m)
    {
        d_status = 0;
        d_loitering = false;
        d_detector.reset();
        d_locator.clear();
        d_centred = false;
        d_x = d_y = 0.0;
        d_first_orbit.clear();
        d_centred_orbits.clear();
        d_held = emitter_location();
        d_candidate = emitter_location();
        d_last_offset = std::numeric_limits<double>::infinity();
        d_next_fit_s = d_cfg.locate_orbits * orbit_s();
        command r = d_inner->update(m);
        r.status = 0;
        return r;
    }

    // Orbit the estimate l from now on (in the air frame it drifts with minus the
    // wind). Returns the time to fly to its orbit.
    double retarget(const emitter_location& l, double t)
    {
        d_target_x = d_x + l.east_m;
        d_target_y = d_y + l.north_m;
        d_target_t = t;
        // The wind moves the estimate in the air frame. One orbit determines it
        // poorly (metres per second of spurious wind, in calm air too, which dragged
        // the centred orbit hundreds of metres away), so the first estimate is
        // orbited in the air frame; later ones with the fitted wind shrunk by one
        // standard error.
        const double wn = std::hypot(l.wind_east_mps, l.wind_north_mps);
        double keep =
            d_centred && wn > 0.0 ? std::max(0.0, 1.0 - l.wind_sigma_mps / wn) : 0.0;
        // Never steer by a wind the vehicle could not hold an orbit in.
        if (keep * wn > MAX_WIND_FRACTION * d_cfg.speed_mps)
            keep = MAX_WIND_FRACTION * d_cfg.speed_mps / wn;
        d_wind_x = keep * l.wind_east_mps;
        d_wind_y = keep * l.wind_north_mps;
        d_centred = true;
        const double r = std::hypot(l.east_m, l.north_m);
        return std::max(0.0, r - d_cfg.loiter_radius_m) / d_cfg.speed_mps;
    }

    // The honest fit of all the loiter's data at time t, unsure and sized as such fits
    // err (size_whole_loiter_fix), else an invalid one: valid, agreeing with the
    // altimeter and within the search area.
    emitter_location whole_loiter_fix(double t) const
    {
        emitter_location now = d_locator.fit(d_x, d_y, true);
        if (!now.valid || !height_agrees(now, d_cfg) ||
            !(std::hypot(now.east_m, now.north_m) <= SEARCH_RADIUS_M))
            return emitter_location();
        if (d_cfg.locate_split_gate > 0.0)
            d_locator.check_split(now, d_cfg.locate_split_gate);
        size_whole_loiter_fix(now, d_cfg);
        now.time_s = t;
        return now;
    }

    // The unsure fix at time t: with the nuisance carried, the fit of all the data (it
    // errs far less than the first confirmed fit carried with its wind). Otherwise, or
    // if that fit fails, the carried fit or a fit of everything now, whichever has the
    // smaller 95 % ellipse; the carried fit's reaching where that fit places the
    // emitter (beyond the search area: the data do not agree with it).
    emitter_location unsure_fix(double t) const
    {
        if (d_cfg.locate_nuisance)
            if (const emitter_location w = whole_loiter_fix(t); w.valid)
                return w;
        emitter_location l = carried_fix(d_candidate, t);
        emitter_location now = d_locator.fit(d_x, d_y, d_cfg.locate_nuisance);
        if (now.valid && height_agrees(now, d_cfg) && d_cfg.locate_split_gate > 0.0)
            d_locator.check_split(now, d_cfg.locate_split_gate);
        if (now.valid && height_agrees(now, d_cfg) && now.major_m < l.major_m) {
            now.unsure = true;
            return now;
        }
        if (d_cfg.locate_nuisance && now.valid && height_agrees(now, d_cfg))
            reach_fit(l, now);
        return l;
    }

    /*
     * The fix of a loiter whose estimate wanders, else an invalid one: not arrived, no
     * fit held back, the last fit within WANDER_CONFIRMS x arrival_confirm_m of the
     * estimate, the orbits placing the emitter near; the fit of all the data
     * (whole_loiter_fix).
     */
    emitter_location wandering_fix(double t) const
    {
        if (d_status != 0 || d_held.valid || !d_centred || !d_cfg.locate_nuisance ||
            !(d_last_offset <= WANDER_CONFIRMS * d_cfg.arrival_confirm_m) ||
            !orbits_place_emitter_near())
            return emitter_location();
        emitter_location now = whole_loiter_fix(t);
        now.wandered = now.valid;
        return now;
    }

    /*
     * The loiter's budget ran out at time t without a published fix. Arrived with a
     * confirmed fix: publish it, unsure. Not arrived: arrive unsure where the orbits
     * show the emitter (a fit held back by the 600 m rule; or, in gusts, fits that
     * wander). Otherwise seek again (returns false) or, without locate_retry, give up.
     */
    bool end_of_budget(double t, command& c)
    {
        if (d_status == 1 && d_candidate.valid) {
            // Arrived, but no fix as tight as the limit within the budget: the last
            // confirmed fix, published as unsure with its honest ellipse.
            publish_fix(unsure_fix(t), c);
        } else if (d_status == 0 && d_held.valid && orbits_place_emitter_near()) {
            // Held back by the 600 m rule to the end of the budget, but the orbits
            // around the estimate swing as they do over the emitter: arrived, and the
            // fix published as unsure with its honest ellipse.
            d_candidate = d_held;
            d_status = 1;              // arrived now; located with the next slot
            d_pending = unsure_fix(t); // published unsure
        } else if (const emitter_location w = wandering_fix(t); w.valid) {
            // No fit agreed with the estimate orbited: in gusts the estimate wanders
            // more than arrival_confirm_m from fit to fit (the last within
            // WANDER_CONFIRMS x it). But the orbits swing as they do over the emitter
            // and a fit of all the data places it by the vehicle: arrived, that fit
            // published as unsure with its honest ellipse.
            d_candidate = w;
            d_status = 1;
            d_pending = w;
        } else {
            // No fix: not the emitter's overflight after all, or too poor a geometry:
            // seek again (the strategy resumes where it was), detect anew.
            if (d_cfg.locate_retry)
                return false;
            d_done = true;
        }
        return true;
    }

    // A fit l that confirms the estimate orbited: arrived (if not yet); its ellipse
    // carries what the flight does not know and is checked against its data's halves
    // (after the retarget, which it does not change); published if sure, else more
    // orbits around this estimate.
    void confirmed(emitter_location l, double loitered, command& c)
    {
        bool honest = false;
        if (d_cfg.locate_nuisance) {
            const emitter_location h = d_locator.fit(d_x, d_y, true);
            if (h.valid) {
                l = h;
                honest = true;
            }
        }
        if (d_cfg.locate_split_gate > 0.0)
            d_locator.check_split(l, d_cfg.locate_split_gate);
        // Arrived only where the honest 95 % ellipse's semi-major axis is within the
        // locator's search area: a false overflight kilometres away can give tight
        // fits by the vehicle under the gust prior, not under the wider gust models;
        // nor where a plane wave does almost as well (far_is_plausible): orbit on.
        if (honest && d_status == 0 && far_is_plausible(l))
            return;
        if (honest && d_status == 0 && !(l.major_m <= SEARCH_RADIUS_M)) {
            d_held = l;
            if (d_retargets++ < MAX_RETARGETS) // more orbits may narrow it
                extend_deadline(loitered, 0.0);
            return;
        }
        const bool fix = l.major_m <= d_cfg.locate_max_axis_m;
        if (!d_candidate.valid) // the first: the least drift in its data
            d_candidate = l;
        if (d_status == 0) { // arrived now; located with the next slot
            d_status = 1;
            if (fix)
                d_pending = l;
            else // time for more fits around this estimate
                extend_deadline(loitered, 0.0);
        } else if (fix) {
            publish_fix(l, c);
        }
    }

    // The fix l is the location: located, done.
    void publish_fix(const emitter_location& l, command& c)
    {
        d_location = l;
        d_status = 2;
        d_done = true;
        c.update = true;
    }

    // After a move of the estimate (transit: the time to get to its orbit) or the
    // arrival: locate_max_orbits - 1 more orbits, and at least one more fit.
    void extend_deadline(double loitered, double transit)
    {
        const double orbits =
            std::max(d_cfg.locate_max_orbits - 1.0, d_cfg.locate_orbits + 0.25);
        d_deadline_s = std::max(d_deadline_s, loitered + transit + orbits * orbit_s());
    }

    // How far the estimate l lies from the one being orbited, carried to now with the
    // wind l fitted (dead-reckoned frame).
    double target_offset(const emitter_location& l, double t) const
    {
        const double ex = d_target_x - l.wind_east_mps * (t - d_target_t);
        const double ey = d_target_y - l.wind_north_mps * (t - d_target_t);
        return std::hypot(d_x + l.east_m - ex, d_y + l.north_m - ey);
    }

    command loiter(const measurement& m)
    {
        command c;
        c.slot = m.slot;
        c.stage = 3;
        // Dead reckoning: the legs since the previous measurement (one per slot: a
        // beacon missed by the receiver leaves a gap) at the mean of the two headings,
        // at the airspeed. The heading is the read smoothed by loiter_heading_gain
        // (heading_filter.h), or the command where there is no read.
        const std::uint64_t slots =
            m.slot > d_last_slot ? std::min<std::uint64_t>(m.slot - d_last_slot, 1000)
                                 : 1;
        d_last_slot = std::max(d_last_slot, m.slot);
        double h = d_heading_cmd;
        if (m.has_heading && std::isfinite(m.heading_rad)) {
            const double since =
                m.slot > d_read_slot ? static_cast<double>(m.slot - d_read_slot) : 1.0;
            h = d_heading_filter.update(m.heading_rad, since * d_cfg.slot_period_s);
            d_read_slot = std::max(d_read_slot, m.slot);
        }
        const double mean = d_last_heading + 0.5 * wrap_remainder(h - d_last_heading);
        const double step = d_cfg.speed_mps * d_cfg.slot_period_s * slots;
        d_x += step * std::cos(mean);
        d_y += step * std::sin(mean);
        d_last_heading = h;
        const bool usable = m.valid && m.snr_db >= d_cfg.min_snr_db &&
                            std::isfinite(m.freq_hz) && !d_done;
        if (usable && !d_centred)
            d_first_orbit.add(m.time_s, h, m.freq_hz);
        if (usable && d_centred && std::isfinite(m.time_s)) {
            d_centred_orbits.push_back({ m.time_s, h, m.freq_hz });
            while (d_centred_orbits.front()[0] < m.time_s - MAX_ORBITS * orbit_s())
                d_centred_orbits.pop_front();
        }
        if (usable)
            d_locator.add(m.time_s,
                          d_x,
                          d_y,
                          d_cfg.speed_mps * std::cos(h),
                          d_cfg.speed_mps * std::sin(h),
                          m.freq_hz);
        c.filtered_freq_hz = m.freq_hz;
        c.accepted = usable;

        const double loitered = m.time_s - d_loiter_start;
        if (d_pending.valid) { // confirmed in the previous slot: publish the fix now
            publish_fix(d_pending, c);
            d_pending = emitter_location();
        } else if (!d_done && loitered >= d_next_fit_s && !d_centred && far_check() &&
                   d_first_orbit.amplitude() >= far_amplitude_hz()) {
            // The first orbit's Doppler swings as far from the emitter: a false
            // overflight (a gust, a turn). Seek on at once.
            return resume_seeking(m);
        } else if (!d_done && loitered >= d_next_fit_s) {
            emitter_location l = d_locator.fit(d_x, d_y);
            // A fit is steered by once its ellipse fits in the locator's search area
            // (one orbit far from the emitter can run off to kilometres).
            const bool usable =
                l.valid && l.major_m <= SEARCH_RADIUS_M && height_agrees(l, d_cfg);
            double next = usable ? d_cfg.locate_orbits : 0.25;
            if (usable) {
                // Arrived once the estimate agrees with the one orbited (carried with
                // the wind now fitted) and lies by the vehicle; a tight enough fix is
                // the location.
                const bool agrees =
                    d_centred &&
                    (d_cfg.arrival_confirm_m <= 0.0 ||
                     (target_offset(l, m.time_s) <= d_cfg.arrival_confirm_m &&
                      std::hypot(l.east_m, l.north_m) <=
                          d_cfg.arrival_confirm_m + d_cfg.loiter_radius_m));
                if (d_centred)
                    d_last_offset = target_offset(l, m.time_s);
                const double transit = retarget(l, m.time_s);
                if (agrees) {
                    confirmed(l, loitered, c);
                } else {
                    // Fly to the new estimate and orbit it; each move (a few at most)
                    // extends the time allowed.
                    next += transit / orbit_s();
                    if (d_retargets++ < MAX_RETARGETS)
                        extend_deadline(loitered, transit);
                }
            }
            d_next_fit_s = loitered + next * orbit_s();
        }
        if (!d_done && !d_pending.valid && loitered >= d_deadline_s &&
            !end_of_budget(m.time_s, c))
            return resume_seeking(m);
        d_heading_cmd = d_centred
                            ? orbit_heading(m.time_s)
                            : wrap_remainder(d_heading_cmd + turn_per_slot() * slots);
        c.heading_rad = d_heading_cmd;
        c.theta_est_rad = theta_est_rad();
        c.status = d_status;
        c.done = d_done;
        c.location = d_location;
        if (d_location.valid) { // the emitter relative to the vehicle now
            c.location.east_m = d_location.east_m + d_location.dr_x_m - d_x;
            c.location.north_m = d_location.north_m + d_location.dr_y_m - d_y;
            c.location.dr_x_m = d_x;
            c.location.dr_y_m = d_y;
        }
        return c;
    }

    /*
     * The heading that keeps the ground track on a circle of loiter_radius_m around the
     * estimated emitter (counter-clockwise): a vector field (tangent, plus a radial pull
     * of 2 (r - R) / R) for the ground course, turned into an air heading through the
     * wind triangle with the estimated wind. Air frame: the emitter moves with -wind.
     */
    double orbit_heading(double t) const
    {
        const double R = d_cfg.loiter_radius_m, v = d_cfg.speed_mps;
        const double ex = d_target_x - d_wind_x * (t - d_target_t);
        const double ey = d_target_y - d_wind_y * (t - d_target_t);
        double ux = d_x - ex, uy = d_y - ey;
        const double r = std::hypot(ux, uy);
        if (r < 1e-6)
            return d_heading_cmd;
        ux /= r;
        uy /= r;
        const double pull = std::clamp(2.0 * (r - R) / R, -2.0, 2.0);
        double cx = -uy - pull * ux, cy = ux - pull * uy; // tangent (CCW) + pull
        const double cn = std::hypot(cx, cy);
        cx /= cn;
        cy /= cn;
        // Ground speed s along the course: |s c - w| = v.
        const double cw = cx * d_wind_x + cy * d_wind_y;
        const double w2 = d_wind_x * d_wind_x + d_wind_y * d_wind_y;
        const double disc = cw * cw - w2 + v * v;
        if (disc <= 0.0) // wind stronger than the airspeed: head into it
            return std::atan2(-d_wind_y, -d_wind_x);
        const double gs = cw + std::sqrt(disc);
        return std::atan2(gs * cy - d_wind_y, gs * cx - d_wind_x);
    }

    seeker_config d_cfg;
    std::unique_ptr<seeker> d_inner;
    overflight_detector d_detector;
    emitter_locator d_locator;
    static constexpr double SEARCH_RADIUS_M = 600.0;         // the locator's grid extent
    static constexpr double MAX_WIND_FRACTION = 0.9;         // of the airspeed
    static constexpr double MIN_FAR_CHECK_ALTITUDE_M = 50.0; // far_check()
    static constexpr double CENTRED_ORBITS = 2.0, MAX_ORBITS = 4.0; // near()
    static constexpr double NEAR_AMPLITUDE_FRACTION = 2.0 / 3.0;    // of the far check's
    static constexpr double WANDER_CONFIRMS = 4.0; // of arrival_confirm_m
    static constexpr int MAX_RETARGETS = 6; // moves of the estimate that extend the time
    int d_status = 0;
    bool d_loitering = false; // stage 3: orbiting (checking, arrived or located)
    bool d_done = false;
    int d_retargets = 0;
    double d_deadline_s = 0.0;    // loiter time after which the vehicle gives up
    emitter_location d_pending;   // confirmed fix, published with the next slot
    emitter_location d_candidate; // the first confirmed fit (published unsure)
    double d_heading_cmd = 0.0, d_last_heading = 0.0, d_loiter_start = 0.0;
    // Time, heading, frequency of the usable measurements of the last MAX_ORBITS
    // orbits around the estimate (orbits_place_emitter_near()).
    std::deque<std::array<double, 3>> d_centred_orbits;
    emitter_location d_held; // the last confirming fit held back by the 600 m rule
    // How far the last fit around an estimate lay from it (target_offset; m).
    double d_last_offset = std::numeric_limits<double>::infinity();
    heading_filter d_heading_filter; // the heading read, smoothed for dead reckoning
    std::uint64_t d_read_slot = 0;   // slot of the last heading read
    double d_x = 0.0, d_y = 0.0;     // dead-reckoned, origin where the loiter began
    std::uint64_t d_last_slot = 0;
    emitter_location d_location;
    double d_next_fit_s;
    bool d_centred = false; // orbiting an estimate (after the first fit)
    double d_target_x = 0.0, d_target_y = 0.0,
           d_target_t = 0.0;               // the estimate, air frame
    double d_wind_x = 0.0, d_wind_y = 0.0; // estimated wind
    doppler_amplitude d_first_orbit;       // the first orbit's measurements
};

} // namespace

std::unique_ptr<seeker> make_homing_seeker(const seeker_config& cfg,
                                           std::unique_ptr<seeker> strategy)
{
    auto s = std::make_unique<homing_seeker>(cfg, std::move(strategy));
    return s;
}

} // namespace rfseek
} // namespace gr
