/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * scenario: validation, derived quantities and by-name access to the run parameters.
 */

#include "parse_setting.h"
#include <gr-rfseek/scenario.h>
#include <nlohmann/json.hpp>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace gr {
namespace rfseek {

namespace {

std::string fmt_num(double v)
{
    // Shortest text that reads back as the same double.
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof(buf), v);
    return std::string(buf, r.ptr);
}

[[noreturn]] void bad(const std::string& field, double value, const std::string& range)
{
    throw std::invalid_argument("scenario." + field + " = " + fmt_num(value) +
                                ": must be " + range);
}

void require_finite(const std::string& field, double v)
{
    if (!std::isfinite(v))
        bad(field, v, "a finite number");
}

void require_range(const std::string& field, double v, double lo, double hi)
{
    if (!(v >= lo && v <= hi))
        bad(field, v, "in [" + fmt_num(lo) + ", " + fmt_num(hi) + "]");
}

void require_positive(const std::string& field, double v)
{
    if (!(v > 0.0) || !std::isfinite(v))
        bad(field, v, "> 0 and finite");
}

void require_nonneg(const std::string& field, double v)
{
    if (!(v >= 0.0) || !std::isfinite(v))
        bad(field, v, ">= 0 and finite");
}

double parse_double(const std::string& key, const std::string& text)
{
    return parse_number("scenario", key, text);
}

enum class kind { real, integer, boolean, optional_real, unsigned64 };

struct field {
    const char* name;
    kind k;
    std::function<void*(scenario&)> ptr;
};

#define RFSEEK_FIELD(NAME, KIND)                                   \
    field                                                          \
    {                                                              \
#NAME, KIND, [](scenario & s) -> void* { return &s.NAME; } \
    }

const std::vector<field>& fields()
{
    static const std::vector<field> f = {
        RFSEEK_FIELD(initial_distance_m, kind::real),
        RFSEEK_FIELD(start_angle_rad, kind::optional_real),
        RFSEEK_FIELD(start_heading_rad, kind::optional_real),
        RFSEEK_FIELD(num_scatterers, kind::integer),
        RFSEEK_FIELD(scatterer_inner_radius_m, kind::real),
        RFSEEK_FIELD(scatterer_outer_radius_m, kind::real),
        RFSEEK_FIELD(gamma_min, kind::real),
        RFSEEK_FIELD(gamma_max, kind::real),
        RFSEEK_FIELD(carrier_hz, kind::real),
        RFSEEK_FIELD(samp_rate_hz, kind::real),
        RFSEEK_FIELD(window_len, kind::integer),
        RFSEEK_FIELD(slot_period_s, kind::real),
        RFSEEK_FIELD(fft_len, kind::integer),
        RFSEEK_FIELD(snr_db, kind::real),
        RFSEEK_FIELD(noise_power_db, kind::real),
        RFSEEK_FIELD(add_noise, kind::boolean),
        RFSEEK_FIELD(cfo_hz, kind::optional_real),
        RFSEEK_FIELD(cfo_range_hz, kind::real),
        RFSEEK_FIELD(cfo_drift_hz_per_s, kind::optional_real),
        RFSEEK_FIELD(cfo_drift_range_hz_per_s, kind::real),
        RFSEEK_FIELD(cfo_walk_hz_per_sqrt_s, kind::real),
        RFSEEK_FIELD(speed_mps, kind::real),
        RFSEEK_FIELD(heading_noise_rad, kind::real),
        RFSEEK_FIELD(turn_rate_rad_per_s, kind::real),
        RFSEEK_FIELD(bank_limit_rad, kind::real),
        RFSEEK_FIELD(roll_rate_rad_per_s, kind::real),
        RFSEEK_FIELD(altitude_m, kind::real),
        RFSEEK_FIELD(wind_speed_mps, kind::real),
        RFSEEK_FIELD(wind_to_rad, kind::optional_real),
        RFSEEK_FIELD(wind_gust_mps, kind::real),
        RFSEEK_FIELD(wind_gust_tau_s, kind::real),
        RFSEEK_FIELD(compass_bias_rad, kind::real),
        RFSEEK_FIELD(compass_noise_rad, kind::real),
        RFSEEK_FIELD(wind_veer_rad_per_s, kind::real),
        RFSEEK_FIELD(airspeed_error_mps, kind::real),
        RFSEEK_FIELD(altimeter_error_m, kind::real),
        RFSEEK_FIELD(wind_forecast, kind::boolean),
        RFSEEK_FIELD(wind_forecast_speed_error_mps, kind::real),
        RFSEEK_FIELD(wind_forecast_direction_error_rad, kind::real),
        RFSEEK_FIELD(success_radius_m, kind::real),
        RFSEEK_FIELD(flight_cap_m, kind::optional_real),
        RFSEEK_FIELD(self_arrival, kind::boolean),
        RFSEEK_FIELD(seed, kind::unsigned64),
    };
    return f;
}
#undef RFSEEK_FIELD

const field& find_field(const std::string& key)
{
    for (const auto& f : fields())
        if (key == f.name)
            return f;
    std::string all;
    for (const auto& f : fields())
        all += (all.empty() ? "" : ", ") + std::string(f.name);
    throw std::invalid_argument("scenario: unknown parameter '" + key +
                                "' (known: " + all + ")");
}

} // namespace

int scenario::slot_samples() const
{
    return static_cast<int>(std::lround(slot_period_s * samp_rate_hz));
}

double scenario::effective_flight_cap_m() const
{
    return flight_cap_m ? *flight_cap_m : 4.0 * shortest_path_m();
}

void scenario::validate() const
{
    require_range("initial_distance_m", initial_distance_m, 1.0, 1.0e7);
    if (start_angle_rad)
        require_finite("start_angle_rad", *start_angle_rad);
    if (start_heading_rad)
        require_finite("start_heading_rad", *start_heading_rad);
    require_range("num_scatterers", num_scatterers, 0, 10000);
    require_nonneg("scatterer_inner_radius_m", scatterer_inner_radius_m);
    require_positive("scatterer_outer_radius_m", scatterer_outer_radius_m);
    if (scatterer_outer_radius_m < scatterer_inner_radius_m)
        bad("scatterer_outer_radius_m",
            scatterer_outer_radius_m,
            ">= scatterer_inner_radius_m (" + fmt_num(scatterer_inner_radius_m) + ")");
    require_range("gamma_min", gamma_min, 0.0, 1.0);
    require_range("gamma_max", gamma_max, gamma_min, 1.0);
    require_range("carrier_hz", carrier_hz, 1.0e3, 1.0e12);
    require_range("samp_rate_hz", samp_rate_hz, 1.0, 1.0e10);
    require_range("slot_period_s", slot_period_s, 1.0e-6, 3600.0);
    require_range("fft_len", fft_len, 4, 1 << 24);
    require_range("window_len", window_len, 3, fft_len);
    if (window_len > slot_samples())
        bad("window_len",
            window_len,
            "<= slot_period_s * samp_rate_hz (" + std::to_string(slot_samples()) +
                "): the beacon must fit in its slot");
    require_range("snr_db", snr_db, -100.0, 100.0);
    require_range("noise_power_db", noise_power_db, -300.0, 100.0);
    require_nonneg("cfo_range_hz", cfo_range_hz);
    require_nonneg("cfo_drift_range_hz_per_s", cfo_drift_range_hz_per_s);
    require_nonneg("cfo_walk_hz_per_sqrt_s", cfo_walk_hz_per_sqrt_s);
    // The UAV must move: a vehicle at rest hears no Doppler to steer by.
    if (!(speed_mps > 0.0 && speed_mps <= 1000.0))
        bad("speed_mps", speed_mps, "in (0, 1000] m/s (the UAV's airspeed)");
    const double nyquist = 0.5 * samp_rate_hz;
    const double fd = max_doppler_hz();
    if (cfo_range_hz + fd >= nyquist)
        bad("cfo_range_hz",
            cfo_range_hz,
            "< samp_rate_hz / 2 - max Doppler (" + fmt_num(nyquist - fd) +
                " Hz) so the beacon stays inside the band");
    if (cfo_hz) {
        require_finite("cfo_hz", *cfo_hz);
        if (std::abs(*cfo_hz) + fd >= nyquist)
            bad("cfo_hz",
                *cfo_hz,
                "in +-" + fmt_num(nyquist - fd) + " Hz (inside the band)");
    }
    if (cfo_drift_hz_per_s)
        require_range("cfo_drift_hz_per_s", *cfo_drift_hz_per_s, -1.0e4, 1.0e4);
    require_range("heading_noise_rad", heading_noise_rad, 0.0, M_PI);
    require_nonneg("turn_rate_rad_per_s", turn_rate_rad_per_s);
    require_range("bank_limit_rad", bank_limit_rad, 0.0, 1.3962634015954636); // 80 deg
    require_range("roll_rate_rad_per_s", roll_rate_rad_per_s, 0.0, 20.0);
    if (roll_rate_rad_per_s > 0.0 && bank_limit_rad == 0.0)
        bad("roll_rate_rad_per_s",
            roll_rate_rad_per_s,
            "0 unless bank_limit_rad > 0 (a roll-rate limit needs a bank limit)");
    require_range("altitude_m", altitude_m, 0.0, 10000.0);
    require_range("wind_speed_mps", wind_speed_mps, 0.0, 100.0);
    if (wind_to_rad)
        require_range("wind_to_rad", *wind_to_rad, -2.0 * M_PI, 2.0 * M_PI);
    require_range("wind_gust_mps", wind_gust_mps, 0.0, 50.0);
    require_range("wind_gust_tau_s", wind_gust_tau_s, 0.01, 3600.0);
    require_range("compass_bias_rad", compass_bias_rad, -M_PI, M_PI);
    require_range("compass_noise_rad", compass_noise_rad, 0.0, M_PI);
    require_range("wind_veer_rad_per_s", wind_veer_rad_per_s, -1.0, 1.0);
    require_finite("airspeed_error_mps", airspeed_error_mps);
    if (!(speed_mps + airspeed_error_mps > 0.0) || std::abs(airspeed_error_mps) > 100.0)
        bad("airspeed_error_mps",
            airspeed_error_mps,
            "in [-100, 100] m/s with speed_mps + airspeed_error_mps > 0 (the airspeed "
            "the vehicle believes)");
    require_finite("altimeter_error_m", altimeter_error_m);
    if (!(altitude_m + altimeter_error_m >= 0.0) || std::abs(altimeter_error_m) > 1e4)
        bad("altimeter_error_m",
            altimeter_error_m,
            "in [-1e4, 1e4] m with altitude_m + altimeter_error_m >= 0 (the altitude "
            "the vehicle believes)");
    require_range("wind_forecast_direction_error_rad",
                  wind_forecast_direction_error_rad,
                  -M_PI,
                  M_PI);
    require_finite("wind_forecast_speed_error_mps", wind_forecast_speed_error_mps);
    if (wind_forecast) {
        const double forecast = wind_speed_mps + wind_forecast_speed_error_mps;
        if (!(forecast >= 0.0 && forecast < speed_mps + airspeed_error_mps))
            bad("wind_forecast_speed_error_mps",
                wind_forecast_speed_error_mps,
                "such that the forecast's speed, wind_speed_mps + this, is in [0, the "
                "believed airspeed)");
    }
    require_range("success_radius_m", success_radius_m, 0.0, initial_distance_m);
    if (flight_cap_m)
        require_positive("flight_cap_m", *flight_cap_m);
}

std::vector<std::string> scenario::keys()
{
    std::vector<std::string> k;
    for (const auto& f : fields())
        k.emplace_back(f.name);
    return k;
}

void scenario::set(const std::string& key, const std::string& value)
{
    const field& f = find_field(key);
    void* p = f.ptr(*this);
    switch (f.k) {
    case kind::real:
        *static_cast<double*>(p) = parse_double(key, value);
        break;
    case kind::integer:
        *static_cast<int*>(p) = parse_int("scenario", key, value);
        break;
    case kind::unsigned64: {
        char* end = nullptr;
        errno = 0;
        const unsigned long long v = std::strtoull(value.c_str(), &end, 10);
        if (value.empty() || *end != '\0' || errno == ERANGE || value[0] == '-')
            throw std::invalid_argument("scenario." + key + ": '" + value +
                                        "' is not a non-negative integer");
        *static_cast<std::uint64_t*>(p) = v;
        break;
    }
    case kind::boolean:
        *static_cast<bool*>(p) = parse_bool("scenario", key, value);
        break;
    case kind::optional_real:
        if (value == "none" || value == "None" || value == "random" || value.empty())
            static_cast<std::optional<double>*>(p)->reset();
        else
            *static_cast<std::optional<double>*>(p) = parse_double(key, value);
        break;
    }
}

std::string scenario::get(const std::string& key) const
{
    const field& f = find_field(key);
    void* p = f.ptr(const_cast<scenario&>(*this));
    switch (f.k) {
    case kind::real:
        return fmt_num(*static_cast<double*>(p));
    case kind::integer:
        return std::to_string(*static_cast<int*>(p));
    case kind::unsigned64:
        return std::to_string(*static_cast<std::uint64_t*>(p));
    case kind::boolean:
        return *static_cast<bool*>(p) ? "true" : "false";
    case kind::optional_real: {
        const auto& o = *static_cast<std::optional<double>*>(p);
        return o ? fmt_num(*o) : "none";
    }
    }
    return "";
}

std::string scenario::to_json() const
{
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const auto& f : fields()) {
        void* p = f.ptr(const_cast<scenario&>(*this));
        switch (f.k) {
        case kind::real:
            j[f.name] = *static_cast<double*>(p);
            break;
        case kind::integer:
            j[f.name] = *static_cast<int*>(p);
            break;
        case kind::unsigned64:
            j[f.name] = *static_cast<std::uint64_t*>(p);
            break;
        case kind::boolean:
            j[f.name] = *static_cast<bool*>(p);
            break;
        case kind::optional_real: {
            const auto& o = *static_cast<std::optional<double>*>(p);
            j[f.name] = o ? nlohmann::ordered_json(*o) : nlohmann::ordered_json(nullptr);
            break;
        }
        }
    }
    return j.dump();
}

namespace {

struct preset_def {
    const char* name;
    const char* description;
    std::vector<std::pair<std::string, std::string>> overrides;
};

// Turn rate 30 deg/s = 0.5235987755982988 rad/s; heading noise 5 deg = 0.0872664626 rad.
const std::vector<preset_def>& preset_table()
{
    static const std::vector<preset_def> table{
        { "reference", "the paper's Table I with docs/design.md's choices", {} },
        { "turn30",
          "turns limited to 30 deg/s",
          { { "turn_rate_rad_per_s", "0.5235987755982988" } } },
        { "start1km",
          "start 1 km from the emitter (SNR 0 dB there)",
          { { "initial_distance_m", "1000" } } },
        { "start10km",
          "start 10 km from the emitter (SNR 0 dB there)",
          { { "initial_distance_m", "10000" } } },
        { "speed20", "20 m/s (f_d,max 133 Hz)", { { "speed_mps", "20" } } },
        { "drift2", "CFO drift fixed at 2 Hz/s", { { "cfo_drift_hz_per_s", "2" } } },
        { "drift10", "CFO drift fixed at 10 Hz/s", { { "cfo_drift_hz_per_s", "10" } } },
        { "snr-15", "initial SNR -15 dB", { { "snr_db", "-15" } } },
        { "snr-22", "initial SNR -22 dB", { { "snr_db", "-22" } } },
        { "hard",
          "30 deg/s turns, initial SNR -10 dB, CFO drift 2 Hz/s, 5 deg heading noise",
          { { "turn_rate_rad_per_s", "0.5235987755982988" },
            { "snr_db", "-10" },
            { "cfo_drift_hz_per_s", "2" },
            { "heading_noise_rad", "0.08726646259971647" } } },
        { "realistic",
          "100 m altitude, 4 m/s wind (1 m/s gusts, 5 s), 3 deg compass bias and 2 deg "
          "noise on what is flown, 30 deg/s turns",
          { { "altitude_m", "100" },
            { "wind_speed_mps", "4" },
            { "wind_gust_mps", "1" },
            { "wind_gust_tau_s", "5" },
            { "compass_bias_rad", "0.05235987755982988" },
            { "compass_noise_rad", "0.03490658503988659" },
            { "turn_rate_rad_per_s", "0.5235987755982988" } } },
        { "windy",
          "a windier day than realistic: 120 m altitude (altimeter +15 m), 6 m/s wind "
          "(2 m/s gusts, 15 s), 4 deg compass bias and 3 deg noise, airspeed believed "
          "0.5 m/s high, 30 deg/s turns",
          { { "altitude_m", "120" },
            { "altimeter_error_m", "15" },
            { "wind_speed_mps", "6" },
            { "wind_gust_mps", "2" },
            { "wind_gust_tau_s", "15" },
            { "compass_bias_rad", "0.06981317007977318" },
            { "compass_noise_rad", "0.05235987755982988" },
            { "airspeed_error_mps", "0.5" },
            { "turn_rate_rad_per_s", "0.5235987755982988" } } },
        { "fixedwing15",
          "a fixed wing at 15 m/s turning as ArduPlane's firmware does (SITL): "
          "coordinated turns at an effective 24.8 deg bank (17 deg/s), 40 deg/s roll "
          "rate",
          { { "speed_mps", "15" },
            { "bank_limit_rad", "0.4328416544945937" },
            { "roll_rate_rad_per_s", "0.6981317007977318" } } },
        { "fixedwing25",
          "a fixed wing at 25 m/s turning as ArduPlane's firmware does (SITL): "
          "coordinated turns at an effective 24.8 deg bank (10.4 deg/s), 40 deg/s roll "
          "rate",
          { { "speed_mps", "25" },
            { "bank_limit_rad", "0.4328416544945937" },
            { "roll_rate_rad_per_s", "0.6981317007977318" } } },
        { "arduplane",
          "ArduPlane's SITL plane in GUIDED, GPS off (docs/sitl.md): 23.6 m/s, 100 m, "
          "turns of 11.0 deg/s (an effective 24.8 deg bank), 40 deg/s roll rate",
          { { "speed_mps", "23.6" },
            { "altitude_m", "100" },
            { "bank_limit_rad", "0.4328416544945937" },
            { "roll_rate_rad_per_s", "0.6981317007977318" } } },
        { "arducopter",
          "ArduCopter's SITL quad in GUIDED_NOGPS at 15 deg of pitch with the link's "
          "coordinated turns (docs/sitl.md): 6.1 m/s, 50 m, 15 deg bank, 30 deg/s roll "
          "rate",
          { { "speed_mps", "6.1" },
            { "altitude_m", "50" },
            { "bank_limit_rad", "0.2617993877991494" },
            { "roll_rate_rad_per_s", "0.5235987755982988" } } },
    };
    return table;
}

const preset_def& find_preset(const std::string& name)
{
    for (const auto& p : preset_table())
        if (name == p.name)
            return p;
    std::string all;
    for (const auto& p : preset_table())
        all += (all.empty() ? "" : ", ") + std::string(p.name);
    throw std::invalid_argument("preset '" + name + "': unknown; one of " + all);
}

} // namespace

std::vector<std::string> scenario::presets()
{
    std::vector<std::string> names;
    for (const auto& p : preset_table())
        names.emplace_back(p.name);
    return names;
}

std::vector<std::pair<std::string, std::string>>
scenario::preset_overrides(const std::string& name)
{
    return find_preset(name).overrides;
}

std::string scenario::preset_description(const std::string& name)
{
    return find_preset(name).description;
}

void scenario::apply_preset(const std::string& name)
{
    for (const auto& kv : find_preset(name).overrides)
        set(kv.first, kv.second);
}

} // namespace rfseek
} // namespace gr
