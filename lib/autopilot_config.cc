/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * autopilot_config: the families, their mode numbers and the settings' checks.
 */

#include <gr-rfseek/autopilot_session.h>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace gr {
namespace rfseek {

namespace {

std::string fmt(double x)
{
    std::ostringstream s;
    s.precision(3);
    s << x;
    return s.str();
}

struct mode_entry {
    autopilot_family family;
    const char* name;
    std::uint32_t number;
};

const std::vector<mode_entry>& mode_table()
{
    using af = autopilot_family;
    static const std::vector<mode_entry> table = {
#define RFSEEK_MAVLINK_MODE(family, name, value) { af::family, name, value },
#include "mavlink_tables.inc"
#undef RFSEEK_MAVLINK_MODE
        // PX4: custom_mode = main mode << 16 (sub mode << 24), px4_custom_mode.h.
        { af::px4, "MANUAL", 1u << 16 },     { af::px4, "ALTCTL", 2u << 16 },
        { af::px4, "POSCTL", 3u << 16 },     { af::px4, "OFFBOARD", 6u << 16 },
        { af::px4, "STABILIZED", 7u << 16 },
    };
    return table;
}

} // namespace

autopilot_family autopilot_family_from_string(const std::string& name)
{
    if (name == "ardupilot_plane" || name == "plane")
        return autopilot_family::ardupilot_plane;
    if (name == "ardupilot_copter" || name == "copter")
        return autopilot_family::ardupilot_copter;
    if (name == "px4")
        return autopilot_family::px4;
    throw std::invalid_argument("autopilot family '" + name +
                                "': must be ardupilot_plane, ardupilot_copter or px4");
}

std::string to_string(autopilot_family f)
{
    switch (f) {
    case autopilot_family::ardupilot_plane:
        return "ardupilot_plane";
    case autopilot_family::ardupilot_copter:
        return "ardupilot_copter";
    default:
        return "px4";
    }
}

std::string autopilot_default_mode(autopilot_family f)
{
    switch (f) {
    case autopilot_family::ardupilot_plane:
        return "GUIDED";
    case autopilot_family::ardupilot_copter:
        return "GUIDED_NOGPS";
    default:
        return "OFFBOARD";
    }
}

std::uint32_t autopilot_mode_number(autopilot_family f, const std::string& mode)
{
    std::string known;
    for (const mode_entry& e : mode_table()) {
        if (e.family != f)
            continue;
        if (mode == e.name)
            return e.number;
        known += (known.empty() ? "" : ", ") + std::string(e.name);
    }
    throw std::invalid_argument("mode '" + mode + "' is not a " + to_string(f) +
                                " mode: one of " + known);
}

void autopilot_config::validate() const
{
    auto positive = [](const char* name, double v, double hi) {
        if (!(v > 0 && v <= hi))
            throw std::invalid_argument(std::string("autopilot_link: ") + name + " = " +
                                        fmt(v) + ": must be in (0, " + fmt(hi) + "]");
    };
    positive("heartbeat_period_s", heartbeat_period_s, 10);
    positive("link_timeout_s", link_timeout_s, 10);
    positive("heartbeat_timeout_s", heartbeat_timeout_s, 30);
    positive("ack_timeout_s", ack_timeout_s, 10);
    positive("command_min_period_s", command_min_period_s, 10);
    positive("setpoint_period_s", setpoint_period_s, 0.5); // PX4 needs >= 2 Hz
    if (retries < 0 || retries > 10)
        throw std::invalid_argument("autopilot_link: retries = " +
                                    std::to_string(retries) + ": must be in [0, 10]");
    if (!(heading_deadband_deg >= 0 && heading_deadband_deg <= 10))
        throw std::invalid_argument("autopilot_link: heading_deadband_deg = " +
                                    fmt(heading_deadband_deg) + ": must be in [0, 10]");
    if (!(airspeed_mps >= 0 && airspeed_mps <= 100))
        throw std::invalid_argument(
            "autopilot_link: airspeed_mps = " + fmt(airspeed_mps) +
            ": must be in [0, 100] (0: the autopilot's own)");
    positive("heading_accel_mps2", heading_accel_mps2, 50);
    positive("command_timeout_s", command_timeout_s, 60);
    if (!(pitch_deg >= 0 && pitch_deg <= 30))
        throw std::invalid_argument("autopilot_link: pitch_deg = " + fmt(pitch_deg) +
                                    ": must be in [0, 30]");
    if (!(thrust >= 0 && thrust <= 1))
        throw std::invalid_argument("autopilot_link: thrust = " + fmt(thrust) +
                                    ": must be in [0, 1]");
    if (!(turn_bank_deg >= 0 && turn_bank_deg <= 30))
        throw std::invalid_argument("autopilot_link: turn_bank_deg = " +
                                    fmt(turn_bank_deg) + ": must be in [0, 30]");
    if (!(turn_speed_mps >= 0 && turn_speed_mps <= 50) ||
        (turn_bank_deg > 0 && turn_speed_mps == 0))
        throw std::invalid_argument(
            "autopilot_link: turn_speed_mps = " + fmt(turn_speed_mps) +
            ": must be in (0, 50] m/s when turn_bank_deg > 0 (the speed at pitch_deg)");
    if (!(declination_deg >= -180 && declination_deg <= 180))
        throw std::invalid_argument(
            "autopilot_link: declination_deg = " + fmt(declination_deg) +
            ": must be in [-180, 180] (deg east of true north)");
    if (target_system == 0 || own_system == 0 || own_component == 0)
        throw std::invalid_argument("autopilot_link: system and component ids must be in "
                                    "[1, 255] (0 is the broadcast address)");
    autopilot_mode_number(family, mode.empty() ? autopilot_default_mode(family) : mode);
}

} // namespace rfseek
} // namespace gr
