/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(autopilot_session.h) */
/* BINDTOOL_HEADER_FILE_HASH(036a30bcec68ac156173b6a418126a7a) */

#include <gr-rfseek/autopilot_session.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace {

using namespace gr::rfseek;

py::dict status_dict(const autopilot_status& s)
{
    py::dict d;
    d["state"] = s.state;
    d["reason"] = s.reason;
    d["armed"] = s.armed;
    d["custom_mode"] = s.custom_mode;
    d["in_mode"] = s.in_mode;
    d["last_heartbeat"] = s.last_heartbeat;
    d["frames"] = s.frames;
    d["heartbeats"] = s.heartbeats;
    d["commands_sent"] = s.commands_sent;
    d["commands_acked"] = s.commands_acked;
    d["commands_failed"] = s.commands_failed;
    d["retries"] = s.retries;
    d["foreign"] = s.foreign;
    d["statustext"] = s.statustext;
    return d;
}

void bind_autopilot_modes(py::module& m)
{
    m.def(
        "autopilot_mode_number",
        [](const std::string& family, const std::string& mode) {
            return autopilot_mode_number(autopilot_family_from_string(family), mode);
        },
        py::arg("family"),
        py::arg("mode"),
        "The custom_mode number of a flight mode of an autopilot family "
        "('ardupilot_plane', 'ardupilot_copter', 'px4').");
    m.def(
        "autopilot_default_mode",
        [](const std::string& family) {
            return autopilot_default_mode(autopilot_family_from_string(family));
        },
        py::arg("family"),
        "The family's mode for seeking: GUIDED, GUIDED_NOGPS or OFFBOARD.");
}

// The multirotors' setpoints: attitude, thrust, coordinated turns, height.
void bind_multirotor_fields(py::class_<autopilot_config>& c)
{
    c.def_readwrite("pitch_deg",
                    &autopilot_config::pitch_deg,
                    "Copter, PX4: forward pitch of the setpoint (deg).")
        .def_readwrite(
            "thrust",
            &autopilot_config::thrust,
            "Copter, PX4: setpoint thrust (ArduCopter GUIDED_NOGPS: 0.5 holds altitude).")
        .def_readwrite("turn_bank_deg",
                       &autopilot_config::turn_bank_deg,
                       "Copter, PX4: the bank of a coordinated turn (deg, [0, 30]): the "
                       "yaw setpoint turns at g tan(bank) / turn_speed_mps, rolled into "
                       "the turn so that the track turns with the yaw. 0: the yaw steps.")
        .def_readwrite("hold_altitude",
                       &autopilot_config::hold_altitude,
                       "PX4: hold the barometric height at which commanding began by "
                       "the thrust (thrust is then the hover thrust).")
        .def_readwrite("turn_speed_mps",
                       &autopilot_config::turn_speed_mps,
                       "Copter, PX4: the speed over the ground at pitch_deg (m/s), for "
                       "the coordinated turn's rate.");
}

void bind_autopilot_config(py::module& m)
{
    auto c =
        py::class_<autopilot_config>(
            m,
            "autopilot_config",
            "Settings of the autopilot link (docs/live.md \"Autopilot\").")
            .def(py::init<>(), "The defaults (ArduPlane, GUIDED, system 1 component 1).")
            .def_property(
                "family",
                [](const autopilot_config& c) { return to_string(c.family); },
                [](autopilot_config& c, const std::string& f) {
                    c.family = autopilot_family_from_string(f);
                },
                "'ardupilot_plane', 'ardupilot_copter' or 'px4': the command path.")
            .def_readwrite(
                "mode", &autopilot_config::mode, "Mode to command in ('': the family's).")
            .def_readwrite("declination_deg",
                           &autopilot_config::declination_deg,
                           "The site's magnetic declination (deg east of true north, "
                           "[-180, 180]): added to reported headings, taken from "
                           "commanded ones, so that the seeker works from true north "
                           "with an autopilot whose compass is magnetic (no GPS).")
            .def_readwrite(
                "target_system",
                &autopilot_config::target_system,
                "The autopilot's system id (reports of any other are dropped).")
            .def_readwrite("target_component",
                           &autopilot_config::target_component,
                           "The autopilot's component id.")
            .def_readwrite(
                "own_system",
                &autopilot_config::own_system,
                "Our system id (a companion computer of the vehicle: the same as "
                "the autopilot's).")
            .def_readwrite("own_component",
                           &autopilot_config::own_component,
                           "Our component id (191: MAV_COMP_ID_ONBOARD_COMPUTER).")
            .def_readwrite("heartbeat_period_s",
                           &autopilot_config::heartbeat_period_s,
                           "Period of our HEARTBEAT (s).")
            .def_readwrite("link_timeout_s",
                           &autopilot_config::link_timeout_s,
                           "Lost when nothing came from the autopilot for this long.")
            .def_readwrite("heartbeat_timeout_s",
                           &autopilot_config::heartbeat_timeout_s,
                           "Lost when no HEARTBEAT came for this long.")
            .def_readwrite("ack_timeout_s",
                           &autopilot_config::ack_timeout_s,
                           "A command unanswered this long is sent again (s).")
            .def_readwrite("retries",
                           &autopilot_config::retries,
                           "Sends after the first before a command has failed.")
            .def_readwrite(
                "heading_deadband_deg",
                &autopilot_config::heading_deadband_deg,
                "ArduPlane: a heading this close to the last one commanded is not "
                "sent again.")
            .def_readwrite(
                "command_min_period_s",
                &autopilot_config::command_min_period_s,
                "ArduPlane: at least this long between two heading commands (s).")
            .def_readwrite(
                "setpoint_period_s",
                &autopilot_config::setpoint_period_s,
                "Copter, PX4: period of the attitude setpoint stream (s, at most 0.5).")
            .def_readwrite("airspeed_mps",
                           &autopilot_config::airspeed_mps,
                           "Commanded airspeed (0: the autopilot's own cruise speed).")
            .def_readwrite(
                "heading_accel_mps2",
                &autopilot_config::heading_accel_mps2,
                "ArduPlane: GUIDED_CHANGE_HEADING param 3, the largest centripetal "
                "acceleration of a heading change (m/s^2; bank up to atan(a/g)).")
            .def_readwrite("command_timeout_s",
                           &autopilot_config::command_timeout_s,
                           "Without a controller command for this long, the link holds.")
            .def_readwrite(
                "request_streams",
                &autopilot_config::request_streams,
                "Ask for ATTITUDE at 20 Hz and VFR_HUD at 4 Hz when the link comes up.")
            .def_property(
                "signing_key",
                [](const autopilot_config& c) -> py::object {
                    if (!c.signing_key)
                        return py::none();
                    return py::bytes(reinterpret_cast<const char*>(c.signing_key->data()),
                                     32);
                },
                [](autopilot_config& c, const py::object& key) {
                    if (key.is_none()) {
                        c.signing_key.reset();
                        return;
                    }
                    const std::string k = key.cast<py::bytes>();
                    if (k.size() != 32)
                        throw py::value_error(
                            "autopilot_config.signing_key: must be 32 bytes "
                            "(or None: no signing)");
                    std::array<std::uint8_t, 32> a;
                    std::copy(k.begin(), k.end(), a.begin());
                    c.signing_key = a;
                },
                "32-byte signing key, or None.")
            .def_readwrite("signing_link_id",
                           &autopilot_config::signing_link_id,
                           "Link id of our signed frames.")
            .def_readwrite("signing_clock_offset_s",
                           &autopilot_config::signing_clock_offset_s,
                           "Seconds from 2015-01-01 UTC to the session's time 0 (signing "
                           "timestamps).")
            .def("validate",
                 &autopilot_config::validate,
                 "ValueError naming a bad field.");
    bind_multirotor_fields(c);
}

} // namespace

void bind_autopilot_session(py::module& m)
{
    bind_autopilot_modes(m);
    bind_autopilot_config(m);
    py::class_<autopilot_session>(
        m,
        "autopilot_session",
        "The autopilot link's rules without sockets: feed it bytes and times, send what "
        "poll() returns.")
        .def(py::init<const autopilot_config&>(),
             py::arg("config"),
             "A session with a validated config (ValueError naming a bad field).")
        .def(
            "receive",
            [](autopilot_session& s, const py::bytes& data, double t) {
                const std::string b = data;
                s.receive(reinterpret_cast<const std::uint8_t*>(b.data()), b.size(), t);
            },
            py::arg("data"),
            py::arg("t"),
            "Bytes from the link at host time t (s).")
        .def("command",
             &autopilot_session::command,
             py::arg("heading_rad"),
             py::arg("t"),
             "The controller's heading (radians counter-clockwise from east).")
        .def("finish",
             &autopilot_session::finish,
             py::arg("t"),
             "The controller is done: stop commanding for good.")
        .def("set_airspeed",
             &autopilot_session::set_airspeed,
             py::arg("airspeed_mps"),
             "A new commanded airspeed (0: the autopilot's own), sent anew.")
        .def(
            "poll",
            [](autopilot_session& s, double t) {
                py::list out;
                for (const auto& f : s.poll(t))
                    out.append(
                        py::bytes(reinterpret_cast<const char*>(f.data()), f.size()));
                return out;
            },
            py::arg("t"),
            "Advance to t; the frames to send now.")
        .def(
            "take_nav",
            [](autopilot_session& s) {
                py::list out;
                for (const auto& n : s.take_nav()) {
                    py::dict d;
                    d["heading"] = n.heading_rad;
                    d["time"] = n.time;
                    if (n.airspeed_mps >= 0)
                        d["airspeed"] = n.airspeed_mps;
                    out.append(d);
                }
                return out;
            },
            "Heading reports since the last call, as dicts {heading, time, airspeed?}.")
        .def(
            "take_status",
            [](autopilot_session& s) {
                py::list out;
                for (const auto& st : s.take_status())
                    out.append(status_dict(st));
                return out;
            },
            "Status snapshots since the last call (one per change).")
        .def(
            "take_log",
            [](autopilot_session& s) {
                py::list out;
                for (const auto& e : s.take_log())
                    out.append(py::make_tuple(
                        e.first,
                        py::bytes(reinterpret_cast<const char*>(e.second.data()),
                                  e.second.size())));
                return out;
            },
            "(time, frame) of every frame received and sent since the last call.")
        .def(
            "status",
            [](const autopilot_session& s) { return status_dict(s.status()); },
            "The current status.")
        .def("autopilot_time",
             &autopilot_session::autopilot_time,
             "The autopilot's clock (s since its boot) in its last ATTITUDE, or None.")
        .def(
            "parser_stats",
            [](const autopilot_session& s) {
                const auto& p = s.parser_stats();
                py::dict d;
                d["frames"] = p.frames;
                d["bad_crc"] = p.bad_crc;
                d["unknown"] = p.unknown;
                d["bad_signature"] = p.bad_signature;
                d["replayed"] = p.replayed;
                d["skipped_bytes"] = p.skipped_bytes;
                return d;
            },
            "The link parser's counters.");
}
