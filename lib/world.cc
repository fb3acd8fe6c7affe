/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * world: emitter, scatterers, UAV kinematics, CFO model and beacon synthesis.
 *
 * Per slot k the UAV is at p_k with heading phi_k. Each path p (LOS, then one per
 * scatterer) arrives with the complex amplitude of its term in eq. 2,
 *   A Gamma_p exp(-j beta L_p) / L_p   (Gamma_LOS = 1, L = path length),
 * and rotates at its own Doppler f_p = (v / lambda) cos(phi_k - psi_p), psi_p the
 * direction from the UAV toward the path's source point (emitter or scatterer):
 * positive when approaching (docs/design.md, item 1). All paths share the carrier offset
 * f_o(t) = f_o(0) + a t + w(t), whose phase is integrated continuously (item 2).
 */

#include "kernels.h"
#include "turn_model.h"
#include <gr-rfseek/world.h>
#include <volk/volk.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace gr {
namespace rfseek {

namespace {
constexpr double TWO_PI = 2.0 * M_PI;
} // namespace

double world::wrap(double a)
{
    a = detail::fmod_exact(a + M_PI, TWO_PI);
    if (a <= 0.0)
        a += TWO_PI;
    return a - M_PI;
}

world::world(const scenario& sc) : d_sc(sc)
{
    d_sc.validate();
    rng g(d_sc.seed, STREAM_GEOMETRY);

    // Draw order is fixed: start angle, start heading, CFO, drift, then scatterers.
    const double alpha = g.uniform(-M_PI, M_PI);
    const double heading = g.uniform(-M_PI, M_PI);
    const double cfo = g.uniform(-1.0, 1.0) * d_sc.cfo_range_hz;
    const double drift = g.uniform(-1.0, 1.0) * d_sc.cfo_drift_range_hz_per_s;
    const double cfo_phase = g.uniform(-M_PI, M_PI);

    const double a0 = d_sc.start_angle_rad.value_or(alpha);
    d_x = d_sc.initial_distance_m * std::cos(a0);
    d_y = d_sc.initial_distance_m * std::sin(a0);
    d_heading = wrap(d_sc.start_heading_rad.value_or(heading));
    d_cfo_hz = d_sc.cfo_hz.value_or(cfo);
    d_cfo_drift = d_sc.cfo_drift_hz_per_s.value_or(drift);
    d_cfo_phase = cfo_phase;
    d_alt = d_sc.altitude_m;

    // Scatterers uniform in the annulus area, angles uniform (Sec. II), Gamma_i with
    // uniform magnitude in [gamma_min, gamma_max] and uniform phase.
    const double r2_in = d_sc.scatterer_inner_radius_m * d_sc.scatterer_inner_radius_m;
    const double r2_out = d_sc.scatterer_outer_radius_m * d_sc.scatterer_outer_radius_m;
    d_scatterers.reserve(d_sc.num_scatterers);
    for (int i = 0; i < d_sc.num_scatterers; ++i) {
        const double r = std::sqrt(g.uniform(r2_in, r2_out));
        const double ang = g.uniform(-M_PI, M_PI);
        const double mag = g.uniform(d_sc.gamma_min, d_sc.gamma_max);
        const double ph = g.uniform(-M_PI, M_PI);
        d_scatterers.push_back(
            { r * std::cos(ang), r * std::sin(ang), std::polar(mag, ph) });
        d_scatterer_range.push_back(
            std::hypot(d_scatterers.back().x_m, d_scatterers.back().y_m));
    }

    // Wind and compass from their own streams: the draws above are those of the flat,
    // windless world whatever the wind.
    if (d_sc.wind_speed_mps > 0.0 || d_sc.wind_gust_mps > 0.0) {
        rng w(d_sc.seed, STREAM_WIND, 0);
        const double to = d_sc.wind_to_rad.value_or(w.uniform(-M_PI, M_PI));
        d_wind_to0 = to;
        d_wind_x = d_sc.wind_speed_mps * std::cos(to);
        d_wind_y = d_sc.wind_speed_mps * std::sin(to);
        d_gust_x = d_sc.wind_gust_mps * w.normal(); // stationary start
        d_gust_y = d_sc.wind_gust_mps * w.normal();
    }
    draw_compass_error(0); // the start heading, as the compass reads it

    // The straight ground line's air distance: ground speed g along the line of sight
    // with the air velocity crabbed so that the crosswind cancels, v^2 = (g - w_par)^2 +
    // w_perp^2, for the path d - d_v.
    const double path = d_sc.shortest_path_m();
    d_straight_air = path;
    if (d_wind_x != 0.0 || d_wind_y != 0.0) {
        const double d = std::hypot(d_x, d_y);
        const double ux = -d_x / d, uy = -d_y / d;
        const double w_par = d_wind_x * ux + d_wind_y * uy;
        const double w_perp = -d_wind_x * uy + d_wind_y * ux;
        const double v = d_sc.speed_mps;
        const double disc = v * v - w_perp * w_perp;
        const double g = disc > 0.0 ? w_par + std::sqrt(disc) : 0.0;
        d_straight_air = g > 0.0 ? path * v / g : std::numeric_limits<double>::infinity();
    }
    // The default cap: 4 x the straight line's air distance, never less than the
    // scenario's calm-air one (a tailwind shortens the way there, not the work near the
    // emitter); a given flight_cap_m is kept.
    const double calm_cap = d_sc.effective_flight_cap_m();
    d_cap = d_sc.flight_cap_m || !std::isfinite(d_straight_air)
                ? calm_cap
                : std::max(calm_cap, 4.0 * d_straight_air);

    update_amplitude();
    draw_measured_heading();
    update_arrival();
}

bool world::flat_and_calm() const
{
    return !d_follow && d_sc.altitude_m == 0.0 && d_sc.wind_speed_mps == 0.0 &&
           d_sc.wind_gust_mps == 0.0;
}

void world::draw_compass_error(std::uint64_t index)
{
    d_compass_err = d_sc.compass_bias_rad;
    if (d_sc.compass_noise_rad > 0.0) {
        rng g(d_sc.seed, STREAM_COMPASS, index);
        d_compass_err += d_sc.compass_noise_rad * g.normal();
    }
}

double world::ground_vx_mps() const
{
    if (d_follow)
        return d_vx;
    return d_sc.speed_mps * std::cos(d_heading) + d_wind_x + d_gust_x;
}

double world::ground_vy_mps() const
{
    if (d_follow)
        return d_vy;
    return d_sc.speed_mps * std::sin(d_heading) + d_wind_y + d_gust_y;
}

double world::slant_range_m() const { return std::hypot(distance_m(), d_alt); }

void world::update_amplitude()
{
    d_noise_power = std::pow(10.0, d_sc.noise_power_db / 10.0);
    const double target = d_noise_power * std::pow(10.0, d_sc.snr_db / 10.0);
    d_amp = std::sqrt(target / mean_field_power(d_sc.initial_distance_m));
}

double world::mean_power_at(double d) const
{
    return d_amp * d_amp * mean_field_power(d);
}

double world::mean_field_power(double d) const
{
    // E|EF|^2 over the positions at distance d: the cross terms average to zero (random
    // scatterer phases), the scattered path length is d_i + r_i with r_i ~ d (slant
    // ranges at altitude).
    if (d_sc.altitude_m > 0.0)
        d = std::hypot(d, d_sc.altitude_m);
    double p = 1.0 / (d * d);
    for (const auto& s : d_scatterers) {
        const double L = std::hypot(s.x_m, s.y_m) + d;
        p += std::norm(s.gamma) / (L * L);
    }
    return p;
}

void world::draw_measured_heading()
{
    rng g(d_sc.seed, STREAM_HEADING, d_slot);
    // The compass reads the flown heading minus its error: it believes it flies the
    // command (x - 0.0 == x: without compass error, the same doubles as before).
    d_measured_heading =
        wrap(d_heading - d_compass_err + d_sc.heading_noise_rad * g.normal());
}

double world::distance_m() const { return std::hypot(d_x, d_y); }

double world::bearing_to_emitter_rad() const { return std::atan2(-d_y, -d_x); }

double world::los_doppler_hz() const
{
    if (flat_and_calm())
        return d_sc.max_doppler_hz() * std::cos(d_heading - bearing_to_emitter_rad());
    // Ground velocity along the unit vector toward the emitter (at ground level).
    return (ground_vx_mps() * -d_x + ground_vy_mps() * -d_y + d_vz * -d_alt) /
           slant_range_m() / d_sc.wavelength_m();
}

void world::fill_paths(std::vector<path_state>& out) const
{
    const double beta = TWO_PI / d_sc.wavelength_m();
    const double fd = d_sc.max_doppler_hz();
    // f = f_d,max cos(heading - psi) = f_d,max (u . heading vector), u the unit vector
    // toward the path's source point: no angle needs computing.
    const double ch = std::cos(d_heading), sh = std::sin(d_heading);
    out.clear();
    if (!flat_and_calm()) {
        // 3-D: the UAV at altitude h, emitter and scatterers on the ground; the Doppler
        // is the ground velocity (air + wind, or the truth's, climbs included) along
        // the unit vector toward each source.
        const double h = d_alt;
        const double inv_lambda = 1.0 / d_sc.wavelength_m();
        const double vx = ground_vx_mps(), vy = ground_vy_mps();
        const double d3 = std::sqrt(d_x * d_x + d_y * d_y + h * h);
        out.push_back(
            { d_amp * detail::polar(1.0 / d3, -detail::fmod_exact(beta * d3, TWO_PI)),
              inv_lambda * (vx * -d_x + vy * -d_y + d_vz * -h) / d3,
              d3 });
        for (std::size_t i = 0; i < d_scatterers.size(); ++i) {
            const auto& s = d_scatterers[i];
            const double dx = s.x_m - d_x, dy = s.y_m - d_y;
            const double ri = std::sqrt(dx * dx + dy * dy + h * h);
            const double L = d_scatterer_range[i] + ri;
            out.push_back(
                { d_amp * s.gamma *
                      detail::polar(1.0 / L, -detail::fmod_exact(beta * L, TWO_PI)),
                  inv_lambda * (vx * dx + vy * dy + d_vz * -h) / ri,
                  L });
        }
        return;
    }
    const double d = distance_m();
    out.push_back({ d_amp * detail::polar(1.0 / d, -detail::fmod_exact(beta * d, TWO_PI)),
                    fd * (ch * -d_x + sh * -d_y) / d,
                    d });
    for (std::size_t i = 0; i < d_scatterers.size(); ++i) {
        const auto& s = d_scatterers[i];
        const double dx = s.x_m - d_x, dy = s.y_m - d_y;
        const double ri = std::hypot(dx, dy);
        const double L = d_scatterer_range[i] + ri;
        out.push_back({ d_amp * s.gamma *
                            detail::polar(1.0 / L, -detail::fmod_exact(beta * L, TWO_PI)),
                        fd * (ch * dx + sh * dy) / ri,
                        L });
    }
}

std::vector<path_state> world::paths() const
{
    std::vector<path_state> out;
    out.reserve(d_scatterers.size() + 1);
    fill_paths(out);
    return out;
}

std::complex<double> world::field() const
{
    if (d_amp <= 0.0)
        return 0.0;
    std::complex<double> ef = 0.0;
    for (const auto& p : paths())
        ef += p.amplitude;
    return ef / d_amp;
}

double world::received_power() const
{
    std::complex<double> s = 0.0;
    for (const auto& p : paths())
        s += p.amplitude;
    return std::norm(s);
}

double world::snr_db() const
{
    return 10.0 * std::log10(std::max(received_power(), 1e-300) / d_noise_power);
}

void world::synthesize(std::complex<float>* out, std::size_t n) const
{
    if (n == 0)
        return;
    const std::size_t nb = std::min<std::size_t>(n, d_sc.window_len);
    const double ts = 1.0 / d_sc.samp_rate_hz;

    // Every path rotates at its Doppler plus the common carrier offset, taken at the
    // middle of the beacon (the drift changes it by a * T, 0.005 Hz at the reference
    // scenario, within the window); the offset's phase is the integral of f_o.
    const double f_o = d_cfo_hz + d_cfo_drift * 0.5 * nb * ts;
    const std::complex<double> rot = std::polar(1.0, d_cfo_phase);
    // Per-thread scratch: no allocation per slot once warm.
    thread_local std::vector<path_state> ps;
    thread_local std::vector<std::complex<double>> amp;
    thread_local std::vector<double> cyc;
    fill_paths(ps);
    amp.resize(ps.size());
    cyc.resize(ps.size());
    for (std::size_t p = 0; p < ps.size(); ++p) {
        amp[p] = ps[p].amplitude * rot;
        cyc[p] = (ps[p].doppler_hz + f_o) * ts;
    }
    const bool noise = d_sc.add_noise;
    std::uint64_t noise_key = 0;
    if (noise) {
        std::uint64_t key = d_sc.seed ^ 0x6E6F697365ULL; // per-slot noise stream
        rng g(key, STREAM_NOISE, d_slot);
        noise_key = g.next();
    }
    detail::tones_and_noise(out,
                            static_cast<std::uint32_t>(n),
                            static_cast<std::uint32_t>(nb),
                            amp.data(),
                            cyc.data(),
                            static_cast<std::uint32_t>(amp.size()),
                            noise,
                            static_cast<float>(std::sqrt(0.5 * d_noise_power)),
                            noise_key);
}

std::vector<std::complex<float>> world::synthesize(std::size_t n) const
{
    std::vector<std::complex<float>> v(n);
    synthesize(v.data(), n);
    return v;
}

void world::advance(double commanded_heading_rad)
{
    if (!std::isfinite(commanded_heading_rad))
        throw std::invalid_argument("world::advance: commanded heading must be finite");
    if (finished())
        throw std::logic_error(
            "world::advance: the run has finished (arrived or capped)");
    if (d_follow)
        throw std::logic_error("world::advance: the world follows a truth (follow())");

    const double dt = d_sc.slot_period_s;
    const double v = d_sc.speed_mps;
    // The vehicle steers by its compass: it flies the command plus the compass error,
    // and its compass then reads the flown heading minus that same error.
    draw_compass_error(d_slot + 1);
    const double target = wrap(commanded_heading_rad + d_compass_err);
    const turn_limits lim{
        d_sc.turn_rate_rad_per_s, d_sc.bank_limit_rad, d_sc.roll_rate_rad_per_s, v
    };
    const double rate = lim.max_rate();

    if (lim.rolls()) { // coordinated turn: the bank follows the roll-rate limit
        coordinated_turn turn(lim, d_heading, d_bank);
        turn.step(target, dt);
        d_heading = turn.heading_rad();
        d_bank = turn.bank_rad();
        d_x += v * turn.path_x();
        d_y += v * turn.path_y();
    } else if (rate <= 0.0) {
        d_heading = target;
        d_x += v * dt * std::cos(d_heading);
        d_y += v * dt * std::sin(d_heading);
    } else {
        // Turn at the maximum rate along an arc until aligned, then fly straight.
        const double err = wrap(target - d_heading);
        const double turn_time = std::min(std::abs(err) / rate, dt);
        const double w = (err >= 0.0 ? rate : -rate);
        if (turn_time > 0.0) {
            const double h1 = d_heading + w * turn_time;
            d_x += (v / w) * (std::sin(h1) - std::sin(d_heading));
            d_y -= (v / w) * (std::cos(h1) - std::cos(d_heading));
            d_heading = h1;
        }
        if (std::abs(wrap(target - d_heading)) < 1e-12)
            d_heading = target;
        d_heading = wrap(d_heading);
        const double straight = dt - turn_time;
        d_x += v * straight * std::cos(d_heading);
        d_y += v * straight * std::sin(d_heading);
    }
    // The air moves the vehicle: mean wind plus gusts, then the gusts' next value
    // (first-order Gauss-Markov, correlation time tau, stationary std wind_gust_mps).
    if (d_wind_x != 0.0 || d_wind_y != 0.0 || d_sc.wind_gust_mps > 0.0) {
        d_x += (d_wind_x + d_gust_x) * dt;
        d_y += (d_wind_y + d_gust_y) * dt;
        if (d_sc.wind_veer_rad_per_s != 0.0) { // the mean wind's direction turns
            const double c = std::cos(d_sc.wind_veer_rad_per_s * dt);
            const double s = std::sin(d_sc.wind_veer_rad_per_s * dt);
            const double wx = d_wind_x;
            d_wind_x = c * wx - s * d_wind_y;
            d_wind_y = s * wx + c * d_wind_y;
        }
        if (d_sc.wind_gust_mps > 0.0) {
            rng w(d_sc.seed, STREAM_WIND, d_slot + 1);
            const double a = std::exp(-dt / d_sc.wind_gust_tau_s);
            const double s = d_sc.wind_gust_mps * std::sqrt(1.0 - a * a);
            d_gust_x = a * d_gust_x + s * w.normal();
            d_gust_y = a * d_gust_y + s * w.normal();
        }
    }
    d_flown += v * dt; // through the air: what the battery pays

    advance_cfo(dt, d_slot);
    ++d_slot;
    update_arrival();
    d_capped = !finished() && d_flown >= d_cap - 1e-9;
    draw_measured_heading();
}

void world::advance_cfo(double dt, std::uint64_t index)
{
    // Integrate the phase over the slot, then step drift and random walk.
    d_cfo_phase =
        wrap(d_cfo_phase + TWO_PI * (d_cfo_hz * dt + 0.5 * d_cfo_drift * dt * dt));
    rng g(d_sc.seed, STREAM_CFO_WALK, index);
    d_cfo_hz +=
        d_cfo_drift * dt + d_sc.cfo_walk_hz_per_sqrt_s * std::sqrt(dt) * g.normal();
}

void world::follow(const vehicle_truth& s)
{
    for (double v : { s.time_s,
                      s.east_m,
                      s.north_m,
                      s.up_m,
                      s.v_east_mps,
                      s.v_north_mps,
                      s.v_up_mps,
                      s.heading_rad })
        if (!std::isfinite(v))
            throw std::invalid_argument("world::follow: every field of the truth must "
                                        "be finite");
    if (finished())
        throw std::logic_error("world::follow: the run has finished (arrived or capped)");
    if (!d_follow) {
        // The first truth places the emitter: the scene (the vehicle's start, the
        // scatterers) turns about the emitter until the scenario's start heading is the
        // truth's, so that the emitter's bearing off the nose and the scatterers are the
        // scenario's (its simulation flies the same geometry); then the truth's frame
        // is moved onto the vehicle's start.
        d_follow = true;
        const double a = wrap(s.heading_rad - d_heading), c = std::cos(a),
                     sn = std::sin(a);
        const double x0 = d_x;
        d_x = c * x0 - sn * d_y;
        d_y = sn * x0 + c * d_y;
        for (auto& sc : d_scatterers) {
            const double sx = sc.x_m;
            sc.x_m = c * sx - sn * sc.y_m;
            sc.y_m = sn * sx + c * sc.y_m;
        }
        d_anchor_x = d_x - s.east_m;
        d_anchor_y = d_y - s.north_m;
    } else {
        const double dt = s.time_s - d_follow_time;
        if (!(dt >= 0.0))
            throw std::invalid_argument(
                "world::follow: time_s = " + std::to_string(s.time_s) +
                ": must not be before the last truth's (" +
                std::to_string(d_follow_time) + ")");
        const double x = s.east_m + d_anchor_x, y = s.north_m + d_anchor_y;
        d_flown += std::hypot(x - d_x, y - d_y); // the true track over the ground
        advance_cfo(dt, d_slot);
        ++d_slot;
        draw_compass_error(d_slot); // what the compass reads of the heading flown
    }
    d_follow_time = s.time_s;
    d_x = s.east_m + d_anchor_x;
    d_y = s.north_m + d_anchor_y;
    d_alt = s.up_m;
    d_vx = s.v_east_mps;
    d_vy = s.v_north_mps;
    d_vz = s.v_up_mps;
    d_heading = wrap(s.heading_rad);
    d_bank = 0.0;
    update_arrival();
    d_capped = !finished() && d_flown >= d_cap - 1e-9;
    draw_measured_heading();
}

void world::update_arrival()
{
    d_arrived = distance_m() <= d_sc.success_radius_m;
    if (d_arrived && !d_reached) {
        d_reached = true;
        d_reached_flown = d_flown;
    }
}

void world::reconfigure(const std::function<void(scenario&)>& change)
{
    scenario s = d_sc;
    change(s);
    s.validate(); // throws before anything changes
    d_sc = s;
    update_amplitude();
}

void world::set_snr_db(double snr_db)
{
    reconfigure([snr_db](scenario& s) { s.snr_db = snr_db; });
}

void world::set_heading_noise_rad(double sigma)
{
    reconfigure([sigma](scenario& s) { s.heading_noise_rad = sigma; });
}

void world::set_turn_rate_rad_per_s(double rate)
{
    reconfigure([rate](scenario& s) { s.turn_rate_rad_per_s = rate; });
}

} // namespace rfseek
} // namespace gr
