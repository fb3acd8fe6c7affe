/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include "angle.h"
#include <gr-rfseek/autopilot_session.h>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace gr {
namespace rfseek {

namespace {

// MAVLink enum values used here (common.xml / minimal.xml).
constexpr std::uint8_t MAV_TYPE_ONBOARD_CONTROLLER = 18;
constexpr std::uint8_t MAV_AUTOPILOT_INVALID = 8;
constexpr std::uint8_t MAV_STATE_ACTIVE = 4;
constexpr std::uint8_t MAV_MODE_FLAG_CUSTOM_MODE_ENABLED = 1;
constexpr std::uint8_t MAV_MODE_FLAG_SAFETY_ARMED = 128;
constexpr std::uint16_t MAV_CMD_DO_CHANGE_SPEED = 178;
constexpr std::uint16_t MAV_CMD_GUIDED_CHANGE_HEADING = 43002;
constexpr float HEADING_TYPE_HEADING = 1;
constexpr float SPEED_TYPE_AIRSPEED = 0;
constexpr std::uint8_t MAV_RESULT_ACCEPTED = 0, MAV_RESULT_TEMPORARILY_REJECTED = 1,
                       MAV_RESULT_IN_PROGRESS = 5;
// SET_ATTITUDE_TARGET type_mask: ignore the three body rates.
constexpr std::uint8_t IGNORE_BODY_RATES = 0x07;

const char* result_name(int r)
{
    static const char* names[] = { "ACCEPTED", "TEMPORARILY_REJECTED",
                                   "DENIED",   "UNSUPPORTED",
                                   "FAILED",   "IN_PROGRESS",
                                   "CANCELLED" };
    return r >= 0 && r < 7 ? names[r] : "an unknown result";
}

// Compass degrees in [0, 360) of a module heading (CCW from east, radians).
double compass_deg(double theta)
{
    double d = std::fmod(90.0 - theta * 180.0 / M_PI, 360.0);
    if (d < 0)
        d += 360.0;
    return d >= 360.0 ? 0.0 : d;
}

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
    if (!(heading_rate_dps >= 0 && heading_rate_dps <= 180))
        throw std::invalid_argument("autopilot_link: heading_rate_dps = " +
                                    fmt(heading_rate_dps) + ": must be in [0, 180]");
    if (!(pitch_deg >= 0 && pitch_deg <= 30))
        throw std::invalid_argument("autopilot_link: pitch_deg = " + fmt(pitch_deg) +
                                    ": must be in [0, 30]");
    if (!(thrust >= 0 && thrust <= 1))
        throw std::invalid_argument("autopilot_link: thrust = " + fmt(thrust) +
                                    ": must be in [0, 1]");
    if (target_system == 0 || own_system == 0 || own_component == 0)
        throw std::invalid_argument("autopilot_link: system and component ids must be in "
                                    "[1, 255] (0 is the broadcast address)");
    autopilot_mode_number(family, mode.empty() ? autopilot_default_mode(family) : mode);
}

autopilot_session::autopilot_session(const autopilot_config& config) : d_cfg(config)
{
    d_cfg.validate();
    if (d_cfg.mode.empty())
        d_cfg.mode = autopilot_default_mode(d_cfg.family);
    d_mode_number = autopilot_mode_number(d_cfg.family, d_cfg.mode);
    if (d_cfg.signing_key)
        d_parser.require_signing(*d_cfg.signing_key, false);
    d_status.reason = "no heartbeat yet from system " +
                      std::to_string(d_cfg.target_system) + " component " +
                      std::to_string(d_cfg.target_component);
    d_reported = d_status;
    d_status_out.push_back(d_status);
}

void autopilot_session::receive(const std::uint8_t* data, std::size_t n, double t)
{
    std::vector<mavlink::frame> frames;
    d_parser.push(data, n, frames);
    for (const mavlink::frame& f : frames) {
        d_log.emplace_back(t, f.raw);
        handle(f, t);
    }
    update_state(t);
}

void autopilot_session::handle(const mavlink::frame& f, double t)
{
    if (f.hdr.sysid != d_cfg.target_system || f.hdr.compid != d_cfg.target_component) {
        ++d_status.foreign; // another system, or another component of ours
        return;
    }
    d_last_frame = t;
    ++d_status.frames;
    if (!f.known())
        return;
    const mavlink::message m = f.decode();
    const std::string& name = m.def().name;
    if (name == "HEARTBEAT") {
        on_heartbeat(m, t);
    } else if (name == "ATTITUDE") {
        // Yaw: radians clockwise from north (NED). Module: counter-clockwise from east.
        const double yaw = m.get("yaw");
        if (std::isfinite(yaw))
            d_nav.push_back({ wrap_remainder(M_PI / 2 - yaw), t, d_airspeed });
    } else if (name == "VFR_HUD") {
        const double a = m.get("airspeed");
        if (std::isfinite(a) && a >= 0)
            d_airspeed = a;
    } else if (name == "COMMAND_ACK") {
        on_ack(m, t);
    } else if (name == "STATUSTEXT") {
        ++d_status.statustext;
    }
    // GLOBAL_POSITION_INT and the rest: in the log only. Position is never passed on.
}

void autopilot_session::on_heartbeat(const mavlink::message& m, double t)
{
    ++d_status.heartbeats;
    d_status.last_heartbeat = t;
    const auto base_mode = static_cast<std::uint8_t>(m.get_uint("base_mode"));
    d_status.armed = (base_mode & MAV_MODE_FLAG_SAFETY_ARMED) != 0;
    d_status.custom_mode = static_cast<std::uint32_t>(m.get_uint("custom_mode"));
    d_status.in_mode = (base_mode & MAV_MODE_FLAG_CUSTOM_MODE_ENABLED) &&
                       d_status.custom_mode == d_mode_number;
}

void autopilot_session::on_ack(const mavlink::message& m, double t)
{
    const auto cmd = static_cast<std::uint16_t>(m.get_uint("command"));
    const int result = static_cast<int>(m.get_uint("result"));
    const auto it =
        std::find_if(d_pending.begin(), d_pending.end(), [&](const pending& p) {
            return p.msg.get_uint("command") == cmd;
        });
    if (it == d_pending.end())
        return; // an ack of something not ours, or already settled
    if (result == MAV_RESULT_ACCEPTED) {
        ++d_status.commands_acked;
        d_pending.erase(it);
    } else if (result == MAV_RESULT_IN_PROGRESS) {
        it->sent_at = t; // wait for the final answer
    } else if (result != MAV_RESULT_TEMPORARILY_REJECTED) {
        ++d_status.commands_failed;
        d_status.reason =
            "command " + std::to_string(cmd) + " refused: " + result_name(result);
        d_pending.erase(it);
    } // TEMPORARILY_REJECTED: sent again at its timeout
}

void autopilot_session::set_state(const std::string& state, const std::string& reason)
{
    const bool was_commanding = commanding();
    d_status.state = state;
    if (state != "commanding" || was_commanding == false)
        d_status.reason = reason;
    if (was_commanding && state != "commanding") {
        // Stop: nothing pending is retried, and on resumption everything is sent anew.
        d_pending.clear();
        d_heading_sent.reset();
        d_speed_sent = false;
    }
}

void autopilot_session::update_state(double t)
{
    const double since_frame = t - d_last_frame;
    const double since_hb = t - d_status.last_heartbeat;
    if (d_status.last_heartbeat < 0)
        set_state("connecting", d_status.reason);
    else if (since_frame > d_cfg.link_timeout_s)
        set_state("lost",
                  "nothing from the autopilot for more than " +
                      fmt(d_cfg.link_timeout_s) + " s (link_timeout_s)");
    else if (since_hb > d_cfg.heartbeat_timeout_s)
        set_state("lost",
                  "no heartbeat for more than " + fmt(d_cfg.heartbeat_timeout_s) +
                      " s (heartbeat_timeout_s)");
    else if (!d_status.armed)
        set_state("holding", "not armed");
    else if (!d_status.in_mode)
        set_state("holding",
                  "mode " + std::to_string(d_status.custom_mode) + ", not " + d_cfg.mode);
    else if (!d_heading)
        set_state("holding", "no heading command from the controller yet");
    else
        set_state("commanding", "");
    report_status();
}

void autopilot_session::report_status()
{
    if (!(d_reported == d_status)) {
        d_reported = d_status;
        d_status_out.push_back(d_status);
    }
}

void autopilot_session::set_airspeed(double airspeed_mps)
{
    autopilot_config c = d_cfg;
    c.airspeed_mps = airspeed_mps;
    c.validate();
    d_cfg.airspeed_mps = airspeed_mps;
    d_speed_sent = false;
}

void autopilot_session::command(double heading_rad, double t)
{
    if (!std::isfinite(heading_rad))
        return;
    d_heading = wrap_remainder(heading_rad);
    update_state(t);
}

void autopilot_session::send(const mavlink::message& m,
                             double t,
                             std::vector<std::vector<std::uint8_t>>& out)
{
    const mavlink::header h{ d_seq++, d_cfg.own_system, d_cfg.own_component };
    std::vector<std::uint8_t> frame;
    if (d_cfg.signing_key) {
        mavlink::signing s;
        s.key = *d_cfg.signing_key;
        s.link_id = d_cfg.signing_link_id;
        // 10 us units; strictly increasing on this stream.
        const double units = std::max(0.0, (t + d_cfg.signing_clock_offset_s) * 1e5);
        d_sign_time = std::max(d_sign_time + 1, static_cast<std::uint64_t>(units));
        frame = mavlink::encode(m, h, &s, d_sign_time);
    } else {
        frame = mavlink::encode(m, h);
    }
    d_log.emplace_back(t, frame);
    out.push_back(std::move(frame));
}

void autopilot_session::queue_command(std::uint16_t cmd,
                                      const std::array<float, 7>& params)
{
    mavlink::message m("COMMAND_LONG");
    m.set("target_system", d_cfg.target_system);
    m.set("target_component", d_cfg.target_component);
    m.set("command", cmd);
    for (int i = 0; i < 7; ++i)
        m.set("param" + std::to_string(i + 1), params[i]);
    // A newer command of the same kind replaces one still awaiting its ack.
    d_pending.erase(std::remove_if(d_pending.begin(),
                                   d_pending.end(),
                                   [&](const pending& p) {
                                       return p.msg.get_uint("command") == cmd;
                                   }),
                    d_pending.end());
    d_pending.push_back({ m, 0.0, 0 });
}

mavlink::message autopilot_session::setpoint() const
{
    // Attitude: roll 0, pitch forward (nose down, negative in NED), yaw the heading
    // (clockwise from north). Quaternion of the 3-2-1 rotation, w x y z.
    const double yaw = M_PI / 2 - *d_heading;
    const double pitch = -d_cfg.pitch_deg * M_PI / 180.0;
    const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
    const double cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
    mavlink::message m("SET_ATTITUDE_TARGET");
    m.set("target_system", d_cfg.target_system);
    m.set("target_component", d_cfg.target_component);
    m.set("type_mask", IGNORE_BODY_RATES);
    m.set("q", cp * cy, 0);
    m.set("q", -sp * sy, 1);
    m.set("q", sp * cy, 2);
    m.set("q", cp * sy, 3);
    m.set("thrust", d_cfg.thrust);
    return m;
}

std::vector<std::vector<std::uint8_t>> autopilot_session::poll(double t)
{
    std::vector<std::vector<std::uint8_t>> out;
    update_state(t);
    if (t - d_last_sent_heartbeat >= d_cfg.heartbeat_period_s) {
        mavlink::message hb("HEARTBEAT");
        hb.set("type", MAV_TYPE_ONBOARD_CONTROLLER);
        hb.set("autopilot", MAV_AUTOPILOT_INVALID);
        hb.set("system_status", MAV_STATE_ACTIVE);
        hb.set("mavlink_version", 3);
        send(hb, t, out);
        d_last_sent_heartbeat = t;
    }
    if (!commanding())
        return out;
    if (d_cfg.family == autopilot_family::ardupilot_plane) {
        if (d_cfg.airspeed_mps > 0 && !d_speed_sent) {
            queue_command(MAV_CMD_DO_CHANGE_SPEED,
                          { SPEED_TYPE_AIRSPEED,
                            static_cast<float>(d_cfg.airspeed_mps),
                            -1.0f,
                            0,
                            0,
                            0,
                            0 });
            d_speed_sent = true;
        }
        const double deadband = d_cfg.heading_deadband_deg * M_PI / 180.0;
        if ((!d_heading_sent ||
             std::abs(wrap_remainder(*d_heading - *d_heading_sent)) > deadband) &&
            t - d_last_heading_sent_at >= d_cfg.command_min_period_s) {
            queue_command(MAV_CMD_GUIDED_CHANGE_HEADING,
                          { HEADING_TYPE_HEADING,
                            static_cast<float>(compass_deg(*d_heading)),
                            static_cast<float>(d_cfg.heading_rate_dps),
                            0,
                            0,
                            0,
                            0 });
            d_heading_sent = d_heading;
            d_last_heading_sent_at = t;
        }
    } else if (t - d_last_setpoint >= d_cfg.setpoint_period_s) {
        mavlink::message m = setpoint();
        m.set("time_boot_ms", std::fmod(std::max(t, 0.0) * 1000.0, 4294967296.0));
        send(m, t, out);
        d_last_setpoint = t;
    }
    // Commands: first sends, and retries of those unanswered.
    for (auto it = d_pending.begin(); it != d_pending.end();) {
        if (it->sends > 0 && t - it->sent_at < d_cfg.ack_timeout_s) {
            ++it;
            continue;
        }
        if (it->sends > d_cfg.retries) {
            ++d_status.commands_failed;
            d_status.reason = "command " + std::to_string(it->msg.get_uint("command")) +
                              ": no ack after " + std::to_string(it->sends) + " sends";
            it = d_pending.erase(it);
            continue;
        }
        if (it->sends > 0)
            ++d_status.retries;
        it->msg.set("confirmation", it->sends); // 0 first, then 1, 2, ...
        ++it->sends;
        it->sent_at = t;
        ++d_status.commands_sent;
        send(it->msg, t, out);
        ++it;
    }
    report_status();
    return out;
}

std::vector<autopilot_nav> autopilot_session::take_nav()
{
    return std::exchange(d_nav, {});
}

std::vector<autopilot_status> autopilot_session::take_status()
{
    return std::exchange(d_status_out, {});
}

std::vector<std::pair<double, std::vector<std::uint8_t>>> autopilot_session::take_log()
{
    return std::exchange(d_log, {});
}

} // namespace rfseek
} // namespace gr
