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
constexpr std::uint16_t MAV_CMD_SET_MESSAGE_INTERVAL = 511;
constexpr std::uint32_t MSG_ATTITUDE = 30, MSG_VFR_HUD = 74;
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

// The same, as the float MAVLink carries: just below 360 would round to 360.0f, which
// autopilots refuse (the range is [0, 360)).
float compass_deg_f(double theta)
{
    const float f = static_cast<float>(compass_deg(theta));
    return f >= 360.0f ? 0.0f : f;
}

std::string fmt(double x)
{
    std::ostringstream s;
    s.precision(3);
    s << x;
    return s.str();
}

} // namespace

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
    if (name != "HEARTBEAT")
        d_streams_seen = true;
    if (name == "HEARTBEAT") {
        on_heartbeat(m, t);
    } else if (name == "ATTITUDE") {
        // Yaw: radians clockwise from north (NED). Module: counter-clockwise from east.
        const double yaw = m.get("yaw");
        if (std::isfinite(yaw)) {
            // In the autopilot's frame (magnetic without GPS); nav from true north.
            d_attitude_yaw = wrap_remainder(M_PI / 2 - yaw);
            d_nav.push_back(
                { wrap_remainder(*d_attitude_yaw - declination()), t, d_airspeed });
            d_autopilot_time = m.get("time_boot_ms") / 1e3;
        }
    } else if (name == "VFR_HUD") {
        const double a = m.get("airspeed");
        if (std::isfinite(a) && a >= 0)
            d_airspeed = a;
        const double alt = m.get("alt"), climb = m.get("climb");
        if (std::isfinite(alt) && std::isfinite(climb)) {
            d_alt = alt;
            d_climb = climb;
        }
    } else if (name == "COMMAND_ACK") {
        on_ack(m, t);
    } else if (name == "STATUSTEXT") {
        ++d_status.statustext;
    }
    // GLOBAL_POSITION_INT and the rest: in the log only. Position is never passed on.
}

void autopilot_session::on_heartbeat(const mavlink::message& m, double t)
{
    if (d_first_heartbeat < 0)
        d_first_heartbeat = t;
    ++d_status.heartbeats;
    d_status.last_heartbeat = t;
    const auto base_mode = static_cast<std::uint8_t>(m.get_uint("base_mode"));
    d_status.armed = (base_mode & MAV_MODE_FLAG_SAFETY_ARMED) != 0;
    d_status.custom_mode = static_cast<std::uint32_t>(m.get_uint("custom_mode"));
    d_status.in_mode = (base_mode & MAV_MODE_FLAG_CUSTOM_MODE_ENABLED) &&
                       d_status.custom_mode == d_mode_number;
}

std::uint16_t autopilot_session::command_of(const pending& p)
{
    return static_cast<std::uint16_t>(p.msg.get_uint("command"));
}

void autopilot_session::on_ack(const mavlink::message& m, double t)
{
    // An ack addressed to someone else (a ground station on the same link) is not ours.
    const auto to_sys = m.get_uint("target_system"),
               to_comp = m.get_uint("target_component");
    if ((to_sys != 0 && to_sys != d_cfg.own_system) ||
        (to_comp != 0 && to_comp != d_cfg.own_component))
        return;
    const auto cmd = static_cast<std::uint16_t>(m.get_uint("command"));
    const int result = static_cast<int>(m.get_uint("result"));
    const auto it =
        std::find_if(d_pending.begin(), d_pending.end(), [&](const pending& p) {
            return p.sends > 0 && command_of(p) == cmd;
        });
    if (it == d_pending.end())
        return; // an ack of something not ours, or already settled
    if (result == MAV_RESULT_ACCEPTED) {
        ++d_status.commands_acked;
        d_pending.erase(it);
    } else if (result == MAV_RESULT_IN_PROGRESS) {
        it->sent_at = t + 2.0; // wait (up to 2 s more) for the final answer, not a retry
    } else if (result != MAV_RESULT_TEMPORARILY_REJECTED) {
        d_pending.erase(it);
        settle_failure(cmd, t, std::string("refused: ") + result_name(result));
    } // TEMPORARILY_REJECTED: sent again at its timeout
}

void autopilot_session::settle_failure(std::uint16_t cmd,
                                       double t,
                                       const std::string& why)
{
    ++d_status.commands_failed;
    d_status.reason = "command " + std::to_string(cmd) + ": " + why;
    // Sent again, a second later at the earliest, even if the controller's value has not
    // changed: a steady heading refused once must not stay unsent.
    if (cmd == MAV_CMD_GUIDED_CHANGE_HEADING) {
        d_heading_sent.reset();
        d_heading_backoff = t + 1.0;
    } else if (cmd == MAV_CMD_DO_CHANGE_SPEED) {
        d_speed_sent = false;
        d_speed_backoff = t + 1.0;
    }
}

void autopilot_session::drop_pending(bool keep_link_requests)
{
    d_pending.erase(std::remove_if(d_pending.begin(),
                                   d_pending.end(),
                                   [&](const pending& p) {
                                       return !keep_link_requests ||
                                              command_of(p) !=
                                                  MAV_CMD_SET_MESSAGE_INTERVAL;
                                   }),
                    d_pending.end());
}

void autopilot_session::set_state(const std::string& state, const std::string& reason)
{
    const bool was_commanding = commanding();
    const bool was_linked = linked();
    d_status.state = state;
    if (state != "commanding" || !was_commanding)
        d_status.reason = reason;
    if (was_commanding && state != "commanding") {
        // Stop: no heading or speed is retried, and on resumption both are sent anew;
        // a coordinated turn starts again from where the vehicle points, the height
        // hold from a fresh report.
        drop_pending(true);
        d_heading_sent.reset();
        d_speed_sent = false;
        d_yaw_sp.reset();
        d_roll_sp = 0;
        d_alt.reset();
    }
    if (was_linked && !linked()) {
        drop_pending(false);
        d_streams_requested = false; // asked again when the link comes back
    }
}

bool autopilot_session::linked() const
{
    return d_status.state == "holding" || d_status.state == "commanding";
}

void autopilot_session::update_state(double t)
{
    const double since_frame = t - d_last_frame;
    const double since_hb = t - d_status.last_heartbeat;
    if (d_status.last_heartbeat < 0)
        set_state("connecting", d_status.reason);
    // Until its streams flow (a port without stream rates set sends heartbeats only,
    // until the interval requests take effect) the link is not called lost for want of
    // them: only the heartbeat timeout applies.
    else if ((d_streams_seen || t - d_first_heartbeat > d_cfg.heartbeat_timeout_s) &&
             since_frame > d_cfg.link_timeout_s)
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
                  "mode " + std::to_string(d_status.custom_mode) + ", not " + d_cfg.mode +
                      (d_cfg.family == autopilot_family::px4
                           ? " (setpoints streamed so that OFFBOARD can be entered)"
                           : ""));
    else if (d_done)
        set_state("holding", "the controller is done");
    else if (!d_heading)
        set_state("holding", "no heading command from the controller yet");
    else if (t - d_last_command > d_cfg.command_timeout_s)
        set_state("holding",
                  "no command from the controller for more than " +
                      fmt(d_cfg.command_timeout_s) + " s (command_timeout_s)");
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
    d_speed_backoff = -1e300;
}

void autopilot_session::finish(double t)
{
    d_done = true;
    update_state(t);
}

void autopilot_session::command(double heading_rad, double t)
{
    if (!std::isfinite(heading_rad))
        return;
    d_heading = wrap_remainder(heading_rad + declination()); // to the autopilot's frame
    d_last_command = t;
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
        // Never behind the autopilot's own clock (a computer without RTC or NTP would
        // otherwise send timestamps it refuses as replays).
        d_sign_time = std::max({ d_sign_time + 1,
                                 static_cast<std::uint64_t>(units),
                                 d_parser.newest_timestamp() + 1 });
        frame = mavlink::encode(m, h, &s, d_sign_time);
    } else {
        frame = mavlink::encode(m, h);
    }
    d_log.emplace_back(t, frame);
    out.push_back(std::move(frame));
}

void autopilot_session::queue_message(mavlink::message m)
{
    m.set("target_system", d_cfg.target_system);
    m.set("target_component", d_cfg.target_component);
    // A newer command of the same kind replaces one still awaiting its ack (message
    // interval requests: of the same message).
    const auto cmd = static_cast<std::uint16_t>(m.get_uint("command"));
    const double key = m.get("param1");
    d_pending.erase(std::remove_if(d_pending.begin(),
                                   d_pending.end(),
                                   [&](const pending& p) {
                                       return command_of(p) == cmd &&
                                              (cmd != MAV_CMD_SET_MESSAGE_INTERVAL ||
                                               p.msg.get("param1") == key);
                                   }),
                    d_pending.end());
    d_pending.push_back({ m, 0.0, 0 });
}

void autopilot_session::queue_command(std::uint16_t cmd,
                                      const std::array<float, 7>& params)
{
    mavlink::message m("COMMAND_LONG");
    m.set("command", cmd);
    for (int i = 0; i < 7; ++i)
        m.set("param" + std::to_string(i + 1), params[i]);
    queue_message(m);
}

void autopilot_session::queue_command_int(std::uint16_t cmd,
                                          const std::array<float, 4>& params)
{
    // COMMAND_INT: ArduPlane handles the GUIDED slew commands only in this form before
    // 4.5 (and in both since). x, y, z unused; frame 0.
    mavlink::message m("COMMAND_INT");
    m.set("command", cmd);
    for (int i = 0; i < 4; ++i)
        m.set("param" + std::to_string(i + 1), params[i]);
    queue_message(m);
}

mavlink::message autopilot_session::setpoint() const
{
    // Attitude: roll (0 unless in a coordinated turn), pitch forward (nose down,
    // negative in NED), yaw the heading (clockwise from north). Quaternion of the 3-2-1
    // rotation, w x y z.
    const double yaw = M_PI / 2 - d_yaw_sp.value_or(*d_heading);
    const double pitch = -d_cfg.pitch_deg * M_PI / 180.0;
    const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
    const double cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
    const double cr = std::cos(d_roll_sp / 2), sr = std::sin(d_roll_sp / 2);
    mavlink::message m("SET_ATTITUDE_TARGET");
    m.set("target_system", d_cfg.target_system);
    m.set("target_component", d_cfg.target_component);
    m.set("type_mask", IGNORE_BODY_RATES);
    m.set("q", cr * cp * cy + sr * sp * sy, 0);
    m.set("q", sr * cp * cy - cr * sp * sy, 1);
    m.set("q", cr * sp * cy + sr * cp * sy, 2);
    m.set("q", cr * cp * sy - sr * sp * cy, 3);
    m.set("thrust", d_thrust_sp);
    return m;
}

void autopilot_session::advance_turn(double t)
{
    if (d_cfg.turn_bank_deg <= 0 || !d_heading) {
        d_yaw_sp.reset();
        d_roll_sp = 0;
        return;
    }
    constexpr double G = 9.80665;
    if (!d_yaw_sp) { // the turn starts from where the vehicle points
        d_yaw_sp = d_attitude_yaw.value_or(*d_heading);
        d_last_turn = t;
    }
    const double dt = std::clamp(t - d_last_turn, 0.0, 1.0);
    d_last_turn = t;
    const double rate_max =
        G * std::tan(d_cfg.turn_bank_deg * M_PI / 180.0) / d_cfg.turn_speed_mps;
    const double step =
        std::clamp(wrap_remainder(*d_heading - *d_yaw_sp), -rate_max * dt, rate_max * dt);
    d_yaw_sp = wrap_remainder(*d_yaw_sp + step);
    // Counter-clockwise (a positive rate) is a left turn: the left wing down, a negative
    // roll in NED; the bank that turns the velocity at that rate, atan(v w / g).
    const double rate = dt > 0 ? step / dt : 0.0;
    d_roll_sp = -std::atan(d_cfg.turn_speed_mps * rate / G);
}

void autopilot_session::hold_altitude(double dt)
{
    d_thrust_sp = d_cfg.thrust;
    if (!d_cfg.hold_altitude || !d_alt || !commanding()) {
        d_alt_ref.reset();
        d_alt_integral = 0;
        return;
    }
    if (!d_alt_ref)
        d_alt_ref = d_alt;
    const double err = *d_alt_ref - *d_alt;
    d_alt_integral = std::clamp(d_alt_integral + err * dt, -100.0, 100.0);
    d_thrust_sp = std::clamp(
        d_cfg.thrust + 0.02 * err + 0.002 * d_alt_integral - 0.05 * d_climb, 0.1, 0.9);
}

bool autopilot_session::streaming() const
{
    // The setpoint stream of the copters: while commanding, and for PX4 also while in
    // another mode, so that OFFBOARD can be entered (PX4 refuses it without a stream
    // and ignores the setpoints outside it). Never without a fresh command.
    if (d_cfg.family == autopilot_family::ardupilot_plane)
        return false;
    if (commanding())
        return true;
    return d_cfg.family == autopilot_family::px4 && d_status.state == "holding" &&
           !d_status.in_mode && !d_done && d_heading && d_status.armed;
}

void autopilot_session::plane_commands(double t)
{
    if (d_cfg.airspeed_mps > 0 && !d_speed_sent && t >= d_speed_backoff) {
        queue_command(MAV_CMD_DO_CHANGE_SPEED,
                      { SPEED_TYPE_AIRSPEED,
                        static_cast<float>(d_cfg.airspeed_mps),
                        -1.0f,
                        0,
                        0,
                        0,
                        0 });
        d_speed_sent = true;
        d_speed_commanded = true;
    } else if (d_cfg.airspeed_mps == 0 && d_speed_commanded && !d_speed_sent &&
               t >= d_speed_backoff) {
        // Back to the autopilot's own speed: -2 is "the default vehicle speed".
        queue_command(MAV_CMD_DO_CHANGE_SPEED,
                      { SPEED_TYPE_AIRSPEED, -2.0f, -1.0f, 0, 0, 0, 0 });
        d_speed_sent = true;
        d_speed_commanded = false;
    }
    const double deadband = d_cfg.heading_deadband_deg * M_PI / 180.0;
    if ((!d_heading_sent ||
         std::abs(wrap_remainder(*d_heading - *d_heading_sent)) > deadband) &&
        t - d_last_heading_sent_at >= d_cfg.command_min_period_s &&
        t >= d_heading_backoff) {
        queue_command_int(MAV_CMD_GUIDED_CHANGE_HEADING,
                          { HEADING_TYPE_HEADING,
                            compass_deg_f(*d_heading),
                            static_cast<float>(d_cfg.heading_accel_mps2),
                            0 });
        d_heading_sent = d_heading;
        d_last_heading_sent_at = t;
    }
}

void autopilot_session::send_pending(double t,
                                     std::vector<std::vector<std::uint8_t>>& out)
{
    // First sends, and retries of those unanswered.
    for (auto it = d_pending.begin(); it != d_pending.end();) {
        if (it->sends > 0 && t - it->sent_at < d_cfg.ack_timeout_s) {
            ++it;
            continue;
        }
        if (it->sends > d_cfg.retries) {
            const std::uint16_t cmd = command_of(*it);
            const int sends = it->sends;
            it = d_pending.erase(it);
            settle_failure(cmd, t, "no ack after " + std::to_string(sends) + " sends");
            continue;
        }
        if (it->sends > 0)
            ++d_status.retries;
        if (it->msg.def().name == "COMMAND_LONG")
            it->msg.set("confirmation", it->sends); // 0 first, then 1, 2, ...
        ++it->sends;
        it->sent_at = t;
        ++d_status.commands_sent;
        send(it->msg, t, out);
        ++it;
    }
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
    if (linked() && d_cfg.request_streams && !d_streams_requested) {
        for (const auto& [id, us] :
             { std::pair<std::uint32_t, float>{ MSG_ATTITUDE, 50000 },
               { MSG_VFR_HUD, 250000 } })
            queue_command(MAV_CMD_SET_MESSAGE_INTERVAL,
                          { static_cast<float>(id), us, 0, 0, 0, 0, 0 });
        d_streams_requested = true;
    }
    if (commanding() && d_cfg.family == autopilot_family::ardupilot_plane)
        plane_commands(t);
    if (streaming() && t - d_last_setpoint >= d_cfg.setpoint_period_s) {
        hold_altitude(std::clamp(t - d_last_setpoint, 0.0, 1.0));
        advance_turn(t);
        mavlink::message m = setpoint();
        m.set("time_boot_ms", std::fmod(std::max(t, 0.0) * 1000.0, 4294967296.0));
        send(m, t, out);
        d_last_setpoint = t;
    }
    if (linked())
        send_pending(t, out);
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
