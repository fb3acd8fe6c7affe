/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * seeker: the strategies' common configuration (validation, settings by name) and the
 * factory. The strategies themselves are one per file (strategies.h lists them).
 */

#include "parse_setting.h"
#include "strategies.h"
#include <gr-rfseek/scenario.h>
#include <gr-rfseek/seeker.h>
#include <gr-rfseek/world.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>

namespace gr {
namespace rfseek {

namespace {

[[noreturn]] void bad(const std::string& field, double v, const std::string& range)
{
    throw std::invalid_argument("seeker_config." + field + " = " + std::to_string(v) +
                                ": must be " + range);
}

std::string short_number(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

void require_finite_field(const char* field, double v)
{
    if (!std::isfinite(v))
        bad(field, v, "a finite number");
}

} // namespace

double seeker_config::max_doppler_hz() const
{
    return speed_mps * carrier_hz / SPEED_OF_LIGHT;
}

double seeker_config::effective_outlier_threshold_hz() const
{
    return outlier_threshold_hz > 0.0 ? outlier_threshold_hz : 2.0 * max_doppler_hz();
}

double seeker_config::far_amplitude() const
{
    // The first harmonic of the Doppler over one orbit of radius R whose centre lies
    // D = 4 R from the emitter, h below (what doppler_amplitude fits), in units of
    // f_d,max: the range rate v u.e_v over the orbit, u the unit line of sight.
    const double R = loiter_radius_m, D = 4.0 * R;
    const double h = std::isfinite(locate_altitude_m) ? std::abs(locate_altitude_m) : 0.0;
    constexpr int N = 360;
    double a = 0.0, b = 0.0;
    for (int k = 0; k < N; ++k) {
        const double psi = 2.0 * M_PI * k / N;
        const double rx = D - R * std::cos(psi), ry = -R * std::sin(psi);
        const double r = std::sqrt(rx * rx + ry * ry + h * h);
        const double f = (-std::sin(psi) * rx + std::cos(psi) * ry) / r;
        a += f * std::cos(psi);
        b += f * std::sin(psi);
    }
    const double geometric = 2.0 * std::hypot(a, b) / N;
    return std::max(arrival_far_amplitude, std::isfinite(geometric) ? geometric : 0.0);
}

namespace {

// The adaptive strategy's and the ground-track guidance's constants.
void validate_adaptive(const seeker_config& c)
{
    if (c.adaptive_acquire_slots < 1 || c.adaptive_acquire_slots > 10000)
        bad("adaptive_acquire_slots", c.adaptive_acquire_slots, "in [1, 10000]");
    if (c.adaptive_relocate_slots < 0 || c.adaptive_relocate_slots > 100000)
        bad("adaptive_relocate_slots", c.adaptive_relocate_slots, "in [0, 100000]");
    if (c.adaptive_track_slots < 1 || c.adaptive_track_slots > 10000)
        bad("adaptive_track_slots", c.adaptive_track_slots, "in [1, 10000]");
    if (!(c.adaptive_turn_share > 0.0 && c.adaptive_turn_share <= 1.0))
        bad("adaptive_turn_share", c.adaptive_turn_share, "in (0, 1]");
    if (!(c.adaptive_gain > 0.0 && c.adaptive_gain <= 1.0))
        bad("adaptive_gain", c.adaptive_gain, "in (0, 1]");
    if (!(c.adaptive_delta_min_rad > 0.0 && c.adaptive_delta_min_rad < M_PI / 2))
        bad("adaptive_delta_min_rad", c.adaptive_delta_min_rad, "in (0, pi/2)");
    if (!(c.adaptive_delta_max_rad >= c.adaptive_delta_min_rad &&
          c.adaptive_delta_max_rad < M_PI / 2))
        bad("adaptive_delta_max_rad",
            c.adaptive_delta_max_rad,
            "in [adaptive_delta_min_rad, pi/2)");
    if (!(c.adaptive_reacquire_rad > 0.0 && c.adaptive_reacquire_rad <= M_PI / 2))
        bad("adaptive_reacquire_rad", c.adaptive_reacquire_rad, "in (0, pi/2]");
    if (!(c.ground_track_gain >= 0.0 && c.ground_track_gain <= 100.0))
        bad("ground_track_gain", c.ground_track_gain, "in [0, 100]");
    if (!(c.paper_ground_track_gain >= 0.0 && c.paper_ground_track_gain <= 100.0))
        bad("paper_ground_track_gain", c.paper_ground_track_gain, "in [0, 100]");
    if (!(c.ground_track_max_crab_rad >= 0.0 && c.ground_track_max_crab_rad < M_PI / 2))
        bad("ground_track_max_crab_rad", c.ground_track_max_crab_rad, "in [0, pi/2)");
    if (!(c.ground_track_gate >= 0.0 && c.ground_track_gate <= 100.0))
        bad("ground_track_gate", c.ground_track_gate, "in [0, 100]");
    if (!(c.ground_track_rate_walk > 0.0 && c.ground_track_rate_walk <= 1.0))
        bad("ground_track_rate_walk",
            c.ground_track_rate_walk,
            "in (0, 1] rad/s/sqrt(s)");
    require_finite_field("wind_forecast_east_mps", c.wind_forecast_east_mps);
    require_finite_field("wind_forecast_north_mps", c.wind_forecast_north_mps);
    const double forecast =
        std::hypot(c.wind_forecast_east_mps, c.wind_forecast_north_mps);
    if (!(forecast < c.speed_mps))
        throw std::invalid_argument(
            "seeker_config.wind_forecast_east_mps, wind_forecast_north_mps = " +
            short_number(c.wind_forecast_east_mps) + ", " +
            short_number(c.wind_forecast_north_mps) + ": the forecast's speed, " +
            short_number(forecast) + " m/s, must be below speed_mps (" +
            short_number(c.speed_mps) + " m/s)");
}

// The constants of arrival without truth and of the emitter locator.
void validate_arrival(const seeker_config& c)
{
    if (!(c.arrival_swing >= 0.5 && c.arrival_swing <= 2.0))
        bad("arrival_swing",
            c.arrival_swing,
            "in [0.5, 2] (x f_d,max; below 0.5 a turn within the band could pass)");
    if (!(c.arrival_window_s > 0.0 && c.arrival_window_s <= 3600.0))
        bad("arrival_window_s", c.arrival_window_s, "in (0, 3600] s");
    if (!(c.arrival_heading_band_rad > 0.0 && c.arrival_heading_band_rad <= M_PI))
        bad("arrival_heading_band_rad", c.arrival_heading_band_rad, "in (0, pi]");
    if (!(c.arrival_power_rise_db >= 0.0 && c.arrival_power_rise_db <= 100.0))
        bad("arrival_power_rise_db", c.arrival_power_rise_db, "in [0, 100] dB");
    if (!(c.arrival_near_swing == 0.0 ||
          (c.arrival_near_swing >= 0.5 && c.arrival_near_swing <= c.arrival_swing)))
        bad("arrival_near_swing",
            c.arrival_near_swing,
            "0 (off) or in [0.5, arrival_swing] (x f_d,max)");
    if (!(c.arrival_near_power_db >= 0.0 && c.arrival_near_power_db <= 100.0))
        bad("arrival_near_power_db", c.arrival_near_power_db, "in [0, 100] dB");
    if (c.arrival_block_slots < 1 || c.arrival_block_slots > 100000)
        bad("arrival_block_slots", c.arrival_block_slots, "in [1, 100000]");
    if (c.arrival_confirm_blocks < 1 || c.arrival_confirm_blocks > 1000)
        bad("arrival_confirm_blocks", c.arrival_confirm_blocks, "in [1, 1000]");
    if (!(c.arrival_encircle >= 0.0 && c.arrival_encircle <= 1.0))
        bad("arrival_encircle", c.arrival_encircle, "in [0, 1] (x f_d,max; 0: off)");
    if (!(c.arrival_far_amplitude >= 0.0 && c.arrival_far_amplitude <= 2.0))
        bad("arrival_far_amplitude",
            c.arrival_far_amplitude,
            "in [0, 2] (x f_d,max; 0: off)");
    if (!(c.arrival_confirm_m >= 0.0 && c.arrival_confirm_m <= 1e5))
        bad("arrival_confirm_m",
            c.arrival_confirm_m,
            "in [0, 1e5] m (0: no confirmation)");
    if (!(c.loiter_radius_m >= c.speed_mps * c.slot_period_s / M_PI &&
          c.loiter_radius_m <= 1e5))
        bad("loiter_radius_m", c.loiter_radius_m, "in [v T_slot / pi, 1e5] m");
    if (!(c.loiter_heading_gain > 0.0 && c.loiter_heading_gain <= 1.0))
        bad("loiter_heading_gain",
            c.loiter_heading_gain,
            "in (0, 1] (1: the heading read itself)");
    const turn_limits lim = turn_limits_of(c);
    if (c.self_arrival && lim.limited() && c.loiter_radius_m < lim.min_radius_m())
        bad("loiter_radius_m",
            c.loiter_radius_m,
            ">= the tightest turn, speed_mps / turn rate (an orbit the vehicle can "
            "turn)");
    if (!(c.locate_orbits > 0.0 && c.locate_orbits <= 100.0))
        bad("locate_orbits", c.locate_orbits, "in (0, 100]");
    if (!(c.locate_max_orbits >= c.locate_orbits && c.locate_max_orbits <= 1000.0))
        bad("locate_max_orbits", c.locate_max_orbits, "in [locate_orbits, 1000]");
    if (!(c.locate_max_axis_m > 0.0) || !std::isfinite(c.locate_max_axis_m))
        bad("locate_max_axis_m", c.locate_max_axis_m, "> 0");
    if (!(c.locate_gust_mps >= 0.0 && c.locate_gust_mps <= 50.0))
        bad("locate_gust_mps", c.locate_gust_mps, "in [0, 50] m/s");
    if (!(c.locate_gust_tau_s >= 0.1 && c.locate_gust_tau_s <= 3600.0))
        bad("locate_gust_tau_s", c.locate_gust_tau_s, "in [0.1, 3600] s");
    if (!(c.locate_split_gate >= 0.0 && c.locate_split_gate <= 1e6))
        bad("locate_split_gate", c.locate_split_gate, "0 (off) or in (0, 1e6]");
    if (!(c.locate_altimeter_range_m >= 0.0 && c.locate_altimeter_range_m <= 1000.0))
        bad("locate_altimeter_range_m", c.locate_altimeter_range_m, "in [0, 1000] m");
    if (!(c.locate_scale95 >= 0.1 && c.locate_scale95 <= 10.0))
        bad("locate_scale95", c.locate_scale95, "in [0.1, 10] (1: as calibrated)");
    if (!(c.locate_scale50 >= 0.1 && c.locate_scale50 <= 10.0))
        bad("locate_scale50", c.locate_scale50, "in [0.1, 10] (1: as calibrated)");
    if (!std::isnan(c.locate_altitude_m) &&
        !(c.locate_altitude_m >= 0.0 && c.locate_altitude_m <= 1e4))
        bad("locate_altitude_m", c.locate_altitude_m, "in [0, 1e4] m, or NaN (unknown)");
    if (!(c.locate_altitude_sigma_m >= 0.0 && c.locate_altitude_sigma_m <= 1e4))
        bad("locate_altitude_sigma_m",
            c.locate_altitude_sigma_m,
            "in [0, 1e4] m (0: none)");
}

} // namespace

void seeker_config::validate() const
{
    require_strategy(strategy, "seeker_config.strategy");
    if (!(speed_mps > 0.0) || !std::isfinite(speed_mps))
        bad("speed_mps", speed_mps, "> 0");
    if (!(carrier_hz > 0.0) || !std::isfinite(carrier_hz))
        bad("carrier_hz", carrier_hz, "> 0");
    if (!(slot_period_s > 0.0) || !std::isfinite(slot_period_s))
        bad("slot_period_s", slot_period_s, "> 0");
    if (!(delta_rad > 0.0 && delta_rad < M_PI / 2))
        bad("delta_rad", delta_rad, "in (0, pi/2)");
    if (!(delta_max_rad >= 0.0 && delta_max_rad < M_PI / 2))
        bad("delta_max_rad", delta_max_rad, "in [0, pi/2) (<= delta_rad: delta fixed)");
    if (!(delta_step_rad > 0.0 && delta_step_rad < M_PI / 2))
        bad("delta_step_rad", delta_step_rad, "in (0, pi/2)");
    if (delta_after_steps < 1 || delta_after_steps > 1000)
        bad("delta_after_steps", delta_after_steps, "in [1, 1000]");
    if (m_slots < 1 || m_slots > 100000)
        bad("m_slots", m_slots, "in [1, 100000]");
    if (!(circle_radius_m > 0.0) || !std::isfinite(circle_radius_m))
        bad("circle_radius_m", circle_radius_m, "> 0");
    if (circle_radius_m < speed_mps * slot_period_s / M_PI)
        bad("circle_radius_m",
            circle_radius_m,
            ">= v T_slot / pi (at least 2 slots per turn)");
    if (moving_average_len < 1 || moving_average_len > 100000)
        bad("moving_average_len", moving_average_len, "in [1, 100000]");
    if (!(outlier_threshold_hz >= 0.0) || !std::isfinite(outlier_threshold_hz))
        bad("outlier_threshold_hz", outlier_threshold_hz, ">= 0 (0 = 2 f_d,max)");
    if (relock_count < 1 || relock_count > 1000)
        bad("relock_count", relock_count, "in [1, 1000]");
    if (!(turn_rate_rad_per_s >= 0.0) || !std::isfinite(turn_rate_rad_per_s))
        bad("turn_rate_rad_per_s", turn_rate_rad_per_s, ">= 0 (0 = instantaneous)");
    if (!(bank_limit_rad >= 0.0 && bank_limit_rad <= 1.3962634015954636))
        bad("bank_limit_rad", bank_limit_rad, "in [0, 80 deg] (0 = no bank limit)");
    if (!(roll_rate_rad_per_s >= 0.0 && roll_rate_rad_per_s <= 20.0))
        bad("roll_rate_rad_per_s",
            roll_rate_rad_per_s,
            "in [0, 20] rad/s (0 = instantaneous)");
    if (roll_rate_rad_per_s > 0.0 && bank_limit_rad == 0.0)
        bad("roll_rate_rad_per_s",
            roll_rate_rad_per_s,
            "0 unless bank_limit_rad > 0 (a roll-rate limit needs a bank limit)");
    if (hold_after_missing < 1)
        bad("hold_after_missing", hold_after_missing, ">= 1");
    if (!(rss_block_m >= 1.0 && rss_block_m <= 100000.0))
        bad("rss_block_m", rss_block_m, "in [1, 100000] m");
    if (rss_window_blocks < 1 || rss_window_blocks > 1000)
        bad("rss_window_blocks", rss_window_blocks, "in [1, 1000]");
    if (!(rss_fall_db >= 0.0 && rss_fall_db <= 60.0))
        bad("rss_fall_db", rss_fall_db, "in [0, 60] dB");
    if (lock_count < 1 || lock_count > 1000)
        bad("lock_count", lock_count, "in [1, 1000]");
    if (std::isnan(min_snr_db) || min_snr_db > 100.0)
        bad("min_snr_db", min_snr_db, "<= 100 dB (-inf: no gate)");
    validate_adaptive(*this);
    validate_arrival(*this);
    if (initial_heading_rad && !std::isfinite(*initial_heading_rad))
        bad("initial_heading_rad", *initial_heading_rad, "finite");
}

std::vector<std::string> seeker_config::keys()
{
    return { "strategy",
             "speed_mps",
             "carrier_hz",
             "slot_period_s",
             "delta_rad",
             "delta_deg",
             "delta_max_rad",
             "delta_max_deg",
             "delta_step_rad",
             "delta_step_deg",
             "delta_after_steps",
             "m_slots",
             "circle_radius_m",
             "moving_average_len",
             "outlier_threshold_hz",
             "literal_eq4",
             "relock_count",
             "turn_rate_rad_per_s",
             "bank_limit_rad",
             "bank_limit_deg",
             "roll_rate_rad_per_s",
             "roll_rate_deg_per_s",
             "hold_after_missing",
             "initial_heading_rad",
             "seed",
             "rss_block_m",
             "rss_window_blocks",
             "rss_fall_db",
             "lock_count",
             "min_snr_db",
             "stage1_fit",
             "adaptive_acquire_slots",
             "adaptive_relocate_slots",
             "adaptive_track_slots",
             "adaptive_turn_share",
             "adaptive_gain",
             "adaptive_delta_min_rad",
             "adaptive_delta_min_deg",
             "adaptive_delta_max_rad",
             "adaptive_delta_max_deg",
             "adaptive_reacquire_rad",
             "adaptive_reacquire_deg",
             "adaptive_drift",
             "adaptive_scatter_delta",
             "adaptive_ground_track",
             "ground_track_gain",
             "ground_track_max_crab_rad",
             "ground_track_max_crab_deg",
             "ground_track_gate",
             "ground_track_rate_walk",
             "wind_forecast_east_mps",
             "wind_forecast_north_mps",
             "paper_ground_track",
             "paper_ground_track_gain",
             "self_arrival",
             "arrival_swing",
             "arrival_window_s",
             "arrival_heading_band_rad",
             "arrival_heading_band_deg",
             "arrival_power_rise_db",
             "arrival_near_swing",
             "arrival_near_power_db",
             "arrival_block_slots",
             "arrival_confirm_blocks",
             "arrival_encircle",
             "arrival_far_amplitude",
             "arrival_confirm_m",
             "loiter_radius_m",
             "loiter_heading_gain",
             "locate_orbits",
             "locate_max_orbits",
             "locate_retry",
             "locate_max_axis_m",
             "locate_gust_mps",
             "locate_gust_tau_s",
             "locate_split_gate",
             "locate_nuisance",
             "locate_altimeter_range_m",
             "locate_scale95",
             "locate_scale50",
             "locate_altitude_m",
             "locate_altitude_sigma_m" };
}

namespace {

// How set() reads a key: a number, degrees into a radian field, an integer or a bool.
enum class setting { real, degrees, integer, boolean };

struct seeker_setting {
    setting kind;
    void* (*member)(seeker_config&);
};

#define RFSEEK_SETTING(KEY, MEMBER, KIND)                                      \
    {                                                                          \
#KEY,                                                                  \
        {                                                                      \
            setting::KIND, [](seeker_config& c) -> void* { return &c.MEMBER; } \
        }                                                                      \
    }

// Every key of set() but strategy, seed and initial_heading_rad.
const std::map<std::string, seeker_setting>& settings()
{
    static const std::map<std::string, seeker_setting> table = {
        RFSEEK_SETTING(speed_mps, speed_mps, real),
        RFSEEK_SETTING(carrier_hz, carrier_hz, real),
        RFSEEK_SETTING(slot_period_s, slot_period_s, real),
        RFSEEK_SETTING(delta_rad, delta_rad, real),
        RFSEEK_SETTING(delta_deg, delta_rad, degrees),
        RFSEEK_SETTING(delta_max_rad, delta_max_rad, real),
        RFSEEK_SETTING(delta_max_deg, delta_max_rad, degrees),
        RFSEEK_SETTING(delta_step_rad, delta_step_rad, real),
        RFSEEK_SETTING(delta_step_deg, delta_step_rad, degrees),
        RFSEEK_SETTING(delta_after_steps, delta_after_steps, integer),
        RFSEEK_SETTING(m_slots, m_slots, integer),
        RFSEEK_SETTING(circle_radius_m, circle_radius_m, real),
        RFSEEK_SETTING(moving_average_len, moving_average_len, integer),
        RFSEEK_SETTING(outlier_threshold_hz, outlier_threshold_hz, real),
        RFSEEK_SETTING(literal_eq4, literal_eq4, boolean),
        RFSEEK_SETTING(relock_count, relock_count, integer),
        RFSEEK_SETTING(turn_rate_rad_per_s, turn_rate_rad_per_s, real),
        RFSEEK_SETTING(bank_limit_rad, bank_limit_rad, real),
        RFSEEK_SETTING(bank_limit_deg, bank_limit_rad, degrees),
        RFSEEK_SETTING(roll_rate_rad_per_s, roll_rate_rad_per_s, real),
        RFSEEK_SETTING(roll_rate_deg_per_s, roll_rate_rad_per_s, degrees),
        RFSEEK_SETTING(hold_after_missing, hold_after_missing, integer),
        RFSEEK_SETTING(rss_block_m, rss_block_m, real),
        RFSEEK_SETTING(rss_window_blocks, rss_window_blocks, integer),
        RFSEEK_SETTING(rss_fall_db, rss_fall_db, real),
        RFSEEK_SETTING(lock_count, lock_count, integer),
        RFSEEK_SETTING(min_snr_db, min_snr_db, real),
        RFSEEK_SETTING(stage1_fit, stage1_fit, boolean),
        RFSEEK_SETTING(adaptive_acquire_slots, adaptive_acquire_slots, integer),
        RFSEEK_SETTING(adaptive_relocate_slots, adaptive_relocate_slots, integer),
        RFSEEK_SETTING(adaptive_track_slots, adaptive_track_slots, integer),
        RFSEEK_SETTING(adaptive_turn_share, adaptive_turn_share, real),
        RFSEEK_SETTING(adaptive_gain, adaptive_gain, real),
        RFSEEK_SETTING(adaptive_delta_min_rad, adaptive_delta_min_rad, real),
        RFSEEK_SETTING(adaptive_delta_min_deg, adaptive_delta_min_rad, degrees),
        RFSEEK_SETTING(adaptive_delta_max_rad, adaptive_delta_max_rad, real),
        RFSEEK_SETTING(adaptive_delta_max_deg, adaptive_delta_max_rad, degrees),
        RFSEEK_SETTING(adaptive_reacquire_rad, adaptive_reacquire_rad, real),
        RFSEEK_SETTING(adaptive_reacquire_deg, adaptive_reacquire_rad, degrees),
        RFSEEK_SETTING(adaptive_drift, adaptive_drift, boolean),
        RFSEEK_SETTING(adaptive_scatter_delta, adaptive_scatter_delta, boolean),
        RFSEEK_SETTING(adaptive_ground_track, adaptive_ground_track, boolean),
        RFSEEK_SETTING(ground_track_gain, ground_track_gain, real),
        RFSEEK_SETTING(ground_track_max_crab_rad, ground_track_max_crab_rad, real),
        RFSEEK_SETTING(ground_track_max_crab_deg, ground_track_max_crab_rad, degrees),
        RFSEEK_SETTING(ground_track_gate, ground_track_gate, real),
        RFSEEK_SETTING(ground_track_rate_walk, ground_track_rate_walk, real),
        RFSEEK_SETTING(wind_forecast_east_mps, wind_forecast_east_mps, real),
        RFSEEK_SETTING(wind_forecast_north_mps, wind_forecast_north_mps, real),
        RFSEEK_SETTING(paper_ground_track, paper_ground_track, boolean),
        RFSEEK_SETTING(paper_ground_track_gain, paper_ground_track_gain, real),
        RFSEEK_SETTING(self_arrival, self_arrival, boolean),
        RFSEEK_SETTING(arrival_swing, arrival_swing, real),
        RFSEEK_SETTING(arrival_window_s, arrival_window_s, real),
        RFSEEK_SETTING(arrival_heading_band_rad, arrival_heading_band_rad, real),
        RFSEEK_SETTING(arrival_heading_band_deg, arrival_heading_band_rad, degrees),
        RFSEEK_SETTING(arrival_power_rise_db, arrival_power_rise_db, real),
        RFSEEK_SETTING(arrival_near_swing, arrival_near_swing, real),
        RFSEEK_SETTING(arrival_near_power_db, arrival_near_power_db, real),
        RFSEEK_SETTING(arrival_block_slots, arrival_block_slots, integer),
        RFSEEK_SETTING(arrival_confirm_blocks, arrival_confirm_blocks, integer),
        RFSEEK_SETTING(arrival_encircle, arrival_encircle, real),
        RFSEEK_SETTING(arrival_far_amplitude, arrival_far_amplitude, real),
        RFSEEK_SETTING(arrival_confirm_m, arrival_confirm_m, real),
        RFSEEK_SETTING(loiter_radius_m, loiter_radius_m, real),
        RFSEEK_SETTING(loiter_heading_gain, loiter_heading_gain, real),
        RFSEEK_SETTING(locate_orbits, locate_orbits, real),
        RFSEEK_SETTING(locate_max_orbits, locate_max_orbits, real),
        RFSEEK_SETTING(locate_retry, locate_retry, boolean),
        RFSEEK_SETTING(locate_max_axis_m, locate_max_axis_m, real),
        RFSEEK_SETTING(locate_gust_mps, locate_gust_mps, real),
        RFSEEK_SETTING(locate_gust_tau_s, locate_gust_tau_s, real),
        RFSEEK_SETTING(locate_split_gate, locate_split_gate, real),
        RFSEEK_SETTING(locate_nuisance, locate_nuisance, boolean),
        RFSEEK_SETTING(locate_altimeter_range_m, locate_altimeter_range_m, real),
        RFSEEK_SETTING(locate_scale95, locate_scale95, real),
        RFSEEK_SETTING(locate_scale50, locate_scale50, real),
        RFSEEK_SETTING(locate_altitude_m, locate_altitude_m, real),
        RFSEEK_SETTING(locate_altitude_sigma_m, locate_altitude_sigma_m, real),
    };
    return table;
}

#undef RFSEEK_SETTING

} // namespace

void seeker_config::set(const std::string& key, const std::string& value)
{
    auto number = [&]() { return parse_number("seeker_config", key, value); };
    if (key == "strategy") {
        strategy = value;
        return;
    }
    if (key == "seed") {
        seed = static_cast<std::uint64_t>(std::strtoull(value.c_str(), nullptr, 10));
        return;
    }
    if (key == "initial_heading_rad") {
        if (value == "none" || value == "None" || value.empty())
            initial_heading_rad.reset();
        else
            initial_heading_rad = number();
        return;
    }
    const auto it = settings().find(key);
    if (it == settings().end())
        throw std::invalid_argument("seeker_config: unknown parameter '" + key + "'");
    void* member = it->second.member(*this);
    switch (it->second.kind) {
    case setting::real:
        *static_cast<double*>(member) = number();
        break;
    case setting::degrees:
        *static_cast<double*>(member) = number() * M_PI / 180.0;
        break;
    case setting::integer:
        *static_cast<int*>(member) = parse_int("seeker_config", key, value);
        break;
    case setting::boolean:
        *static_cast<bool*>(member) = parse_bool("seeker_config", key, value);
        break;
    }
}

std::vector<std::string> seeker::strategies()
{
    return { "paper", "paper_no_circle", "rss_baseline", "adaptive" };
}

std::unique_ptr<seeker> seeker::make(const seeker_config& cfg)
{
    cfg.validate();
    if (cfg.self_arrival) {
        seeker_config inner = cfg;
        inner.self_arrival = false;
        return make_homing_seeker(cfg, make(inner));
    }
    if (cfg.strategy == "rss_baseline")
        return make_rss_seeker(cfg);
    if (cfg.strategy == "adaptive")
        return make_adaptive_seeker(cfg);
    return make_two_stage_seeker(cfg);
}

} // namespace rfseek
} // namespace gr
