/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The autopilot link's rules (include/gr-rfseek/autopilot_session.h) against a scripted
 * autopilot: mode and arming gating, the command path of each family, ack retries, link
 * loss and resumption, foreign systems, signing, and the heading convention.
 */

#include <gr-rfseek/autopilot_session.h>
#include <gtest/gtest.h>
#include <array>
#include <cmath>

using namespace gr::rfseek;
namespace mav = gr::rfseek::mavlink;

namespace {

constexpr std::uint8_t ARMED = 128, CUSTOM = 1;

// A scripted autopilot: system 1, component 1 unless told otherwise.
struct fake_autopilot {
    std::uint8_t sysid = 1, compid = 1, seq = 0;
    const mav::signing* sign = nullptr;
    std::uint64_t sign_time = 1;

    std::vector<std::uint8_t> frame(const mav::message& m)
    {
        return mav::encode(m, mav::header{ seq++, sysid, compid }, sign, sign_time++);
    }
    std::vector<std::uint8_t> heartbeat(std::uint8_t base_mode, std::uint32_t custom_mode)
    {
        mav::message m("HEARTBEAT");
        m.set("type", 1);
        m.set("autopilot", 3);
        m.set("base_mode", base_mode);
        m.set("custom_mode", custom_mode);
        m.set("mavlink_version", 3);
        return frame(m);
    }
    std::vector<std::uint8_t> attitude(double yaw)
    {
        mav::message m("ATTITUDE");
        m.set("yaw", yaw);
        return frame(m);
    }
    std::vector<std::uint8_t> ack(std::uint16_t command, std::uint8_t result)
    {
        mav::message m("COMMAND_ACK");
        m.set("command", command);
        m.set("result", result);
        return frame(m);
    }
};

void feed(autopilot_session& s, const std::vector<std::uint8_t>& bytes, double t)
{
    s.receive(bytes.data(), bytes.size(), t);
}

// The messages among frames the session sent (parsed with `key` when given).
std::vector<mav::message> decode_all(const std::vector<std::vector<std::uint8_t>>& frames,
                                     const std::array<std::uint8_t, 32>* key = nullptr)
{
    mav::parser p;
    if (key)
        p.require_signing(*key);
    std::vector<mav::frame> out;
    for (const auto& f : frames)
        p.push(f.data(), f.size(), out);
    EXPECT_EQ(out.size(), frames.size()) << "a frame we sent did not parse";
    std::vector<mav::message> msgs;
    for (const auto& f : out) {
        EXPECT_EQ(f.hdr.sysid, 1);
        EXPECT_EQ(f.hdr.compid, 191);
        msgs.push_back(f.decode());
    }
    return msgs;
}

std::vector<mav::message> of(const std::vector<mav::message>& msgs,
                             const std::string& name)
{
    std::vector<mav::message> out;
    for (const auto& m : msgs)
        if (m.def().name == name)
            out.push_back(m);
    return out;
}

// The commands among them (COMMAND_LONG and COMMAND_INT), without the link's requests
// for message streams (MAV_CMD_SET_MESSAGE_INTERVAL).
std::vector<mav::message> commands(const std::vector<mav::message>& msgs)
{
    std::vector<mav::message> out;
    for (const auto& m : msgs)
        if ((m.def().name == "COMMAND_LONG" || m.def().name == "COMMAND_INT") &&
            m.get_uint("command") != 511)
            out.push_back(m);
    return out;
}

autopilot_config plane_config()
{
    autopilot_config c;
    c.airspeed_mps = 12;
    return c;
}

} // namespace

TEST(autopilot_session, modes_and_validation)
{
    EXPECT_EQ(autopilot_mode_number(autopilot_family::ardupilot_plane, "GUIDED"), 15u);
    EXPECT_EQ(autopilot_mode_number(autopilot_family::ardupilot_plane, "FLY_BY_WIRE_A"),
              5u);
    EXPECT_EQ(autopilot_mode_number(autopilot_family::ardupilot_copter, "GUIDED_NOGPS"),
              20u);
    EXPECT_EQ(autopilot_mode_number(autopilot_family::px4, "OFFBOARD"), 6u << 16);
    EXPECT_THROW(autopilot_mode_number(autopilot_family::ardupilot_plane, "OFFBOARD"),
                 std::invalid_argument);
    EXPECT_EQ(autopilot_family_from_string("copter"), autopilot_family::ardupilot_copter);
    EXPECT_THROW(autopilot_family_from_string("inav"), std::invalid_argument);
    autopilot_config c;
    c.setpoint_period_s = 1.0; // PX4 leaves OFFBOARD below 2 Hz
    try {
        c.validate();
        FAIL() << "setpoint_period_s = 1 accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("setpoint_period_s"), std::string::npos);
    }
    c = autopilot_config();
    c.target_system = 0;
    EXPECT_THROW(c.validate(), std::invalid_argument);
}

TEST(autopilot_session, commands_only_armed_in_the_named_mode)
{
    autopilot_session s(plane_config());
    fake_autopilot ap;
    s.command(0.0, 0.0); // east: compass 90 deg
    auto msgs = decode_all(s.poll(0.0));
    ASSERT_EQ(msgs.size(), 1u);               // our heartbeat only
    EXPECT_EQ(msgs[0].get_uint("type"), 18u); // MAV_TYPE_ONBOARD_CONTROLLER
    EXPECT_EQ(s.status().state, "connecting");

    feed(s, ap.heartbeat(CUSTOM, 15), 0.1); // GUIDED, disarmed
    EXPECT_TRUE(commands(decode_all(s.poll(0.1))).empty());
    EXPECT_EQ(s.status().state, "holding");
    EXPECT_EQ(s.status().reason, "not armed");

    feed(s, ap.heartbeat(CUSTOM | ARMED, 5), 0.2); // armed, FBWA
    EXPECT_TRUE(commands(decode_all(s.poll(0.2))).empty());
    EXPECT_EQ(s.status().state, "holding");
    EXPECT_NE(s.status().reason.find("not GUIDED"), std::string::npos);

    feed(s, ap.heartbeat(CUSTOM | ARMED, 15), 0.3); // armed, GUIDED
    const auto cmds = commands(decode_all(s.poll(0.3)));
    EXPECT_EQ(s.status().state, "commanding");
    ASSERT_EQ(cmds.size(), 2u);
    EXPECT_EQ(cmds[0].get_uint("command"), 178u); // DO_CHANGE_SPEED
    EXPECT_EQ(cmds[0].get("param1"), 0.0);        // airspeed
    EXPECT_FLOAT_EQ(cmds[0].get("param2"), 12.0);
    EXPECT_EQ(cmds[1].get_uint("command"), 43002u); // GUIDED_CHANGE_HEADING
    EXPECT_EQ(cmds[1].get("param1"), 1.0);          // raw heading
    EXPECT_FLOAT_EQ(cmds[1].get("param2"), 90.0);
    EXPECT_EQ(cmds[1].get_uint("target_system"), 1u);
    EXPECT_EQ(cmds[1].get_uint("target_component"), 1u);

    // Disarmed in flight: commands stop at once, and the status says why.
    feed(s, ap.ack(178, 0), 0.35);
    feed(s, ap.ack(43002, 0), 0.35);
    feed(s, ap.heartbeat(CUSTOM, 15), 0.4);
    s.command(1.0, 0.4);
    EXPECT_TRUE(commands(decode_all(s.poll(0.5))).empty());
    EXPECT_EQ(s.status().reason, "not armed");
    const auto statuses = s.take_status();
    ASSERT_GE(statuses.size(), 4u);
    EXPECT_EQ(statuses.back().state, "holding");
}

TEST(autopilot_session, heading_commands_follow_the_controller)
{
    autopilot_config c;
    c.heading_deadband_deg = 1.0;
    autopilot_session s(c);
    fake_autopilot ap;
    feed(s, ap.heartbeat(CUSTOM | ARMED, 15), 0.0);
    s.command(M_PI / 2, 0.0); // north
    auto cmds = commands(decode_all(s.poll(0.0)));
    ASSERT_EQ(cmds.size(), 1u); // no airspeed set: no DO_CHANGE_SPEED
    EXPECT_FLOAT_EQ(cmds[0].get("param2"), 0.0);
    feed(s, ap.ack(43002, 0), 0.05);
    // Within the deadband: not sent again. Beyond it, but too soon: waits for
    // command_min_period_s.
    feed(s, ap.attitude(0), 0.1);
    s.command(M_PI / 2 - 0.5 * M_PI / 180, 0.1);
    EXPECT_TRUE(commands(decode_all(s.poll(0.1))).empty());
    s.command(M_PI / 2 - 20 * M_PI / 180, 0.15); // 20 deg right: compass 20
    feed(s, ap.attitude(0), 0.15);
    EXPECT_TRUE(commands(decode_all(s.poll(0.15))).empty());
    feed(s, ap.attitude(0), 0.2);
    cmds = commands(decode_all(s.poll(0.2)));
    ASSERT_EQ(cmds.size(), 1u);
    EXPECT_NEAR(cmds[0].get("param2"), 20.0, 1e-4);
}

TEST(autopilot_session, unanswered_commands_are_retried_then_fail)
{
    autopilot_config c;
    c.ack_timeout_s = 0.3;
    c.retries = 3;
    c.request_streams = false; // only the heading awaits an ack here
    autopilot_session s(c);
    fake_autopilot ap;
    s.command(0.0, 0.0);
    std::vector<double> sent_at;
    for (int k = 0; k <= 250; ++k) {
        const double t = 0.01 * k;
        s.command(0.0, t); // the controller, every slot
        if (k % 5 == 0)    // telemetry at 20 Hz, heartbeats at 1 Hz
            feed(
                s, k % 100 == 0 ? ap.heartbeat(CUSTOM | ARMED, 15) : ap.attitude(1.0), t);
        for (const auto& m : commands(decode_all(s.poll(t)))) {
            EXPECT_EQ(m.def().name, "COMMAND_INT"); // ArduPlane's slew commands
            EXPECT_EQ(m.get_uint("command"), 43002u);
            sent_at.push_back(t);
        }
    }
    // First send, then 3 retries 0.3 s apart; then failure; the same heading is sent
    // again a second after the failure (a refused heading must not stay unsent).
    ASSERT_EQ(sent_at.size(), 5u);
    for (std::size_t i = 0; i < 4; ++i)
        EXPECT_NEAR(sent_at[i], 0.3 * i, 0.011);
    EXPECT_NEAR(sent_at[4], 1.2 + 1.0, 0.011);
    EXPECT_EQ(s.status().retries, 3u);
    EXPECT_EQ(s.status().commands_failed, 1u);
    EXPECT_NE(s.status().reason.find("no ack after 4 sends"), std::string::npos);

    // Refused: not retried at once; the reason names the result; sent again after a
    // second. A temporarily rejected command is sent again at its timeout; accepted,
    // it stops.
    autopilot_session r(c);
    fake_autopilot ap2;
    feed(r, ap2.heartbeat(CUSTOM | ARMED, 15), 0.0);
    r.command(0.0, 0.0);
    EXPECT_EQ(commands(decode_all(r.poll(0.0))).size(), 1u);
    feed(r, ap2.ack(43002, 2), 0.1); // DENIED
    EXPECT_EQ(r.status().commands_failed, 1u);
    EXPECT_NE(r.status().reason.find("DENIED"), std::string::npos);
    r.command(0.5, 0.2);
    feed(r, ap2.attitude(0), 0.2);
    EXPECT_TRUE(commands(decode_all(r.poll(0.2))).empty()); // a second after the refusal
    std::vector<double> sends;
    for (int k = 110; k <= 250; ++k) {
        const double t = 0.01 * k;
        r.command(0.5, t);
        if (k % 5 == 0)
            feed(
                r, k % 100 == 0 ? ap2.heartbeat(CUSTOM | ARMED, 15) : ap2.attitude(0), t);
        if (k == 120)
            feed(r, ap2.ack(43002, 1), t); // TEMPORARILY_REJECTED
        if (k == 150)
            feed(r, ap2.ack(43002, 0), t); // ACCEPTED
        if (!commands(decode_all(r.poll(t))).empty())
            sends.push_back(t);
    }
    ASSERT_EQ(sends.size(), 2u);
    EXPECT_NEAR(sends[0], 1.1, 0.011);
    EXPECT_NEAR(sends[1], 1.4, 0.011);
    EXPECT_EQ(r.status().commands_acked, 1u);
}

TEST(autopilot_session, link_loss_stops_commands_within_a_second_and_resumes)
{
    autopilot_config c;
    c.family = autopilot_family::ardupilot_copter;
    autopilot_session s(c);
    fake_autopilot ap;
    s.command(0.3, 0.0);
    double last_setpoint = -1, last_heartbeat = -1, first_after = -1;
    const double silent_from = 5.03; // the autopilot's last frame before this
    for (int k = 0; k <= 1000; ++k) {
        const double t = 0.01 * k;
        const bool talking = t < silent_from || t >= 8.0;
        s.command(0.3, t); // the controller, every slot
        if (talking && k % 5 == 0) {
            const bool hb = k % 100 == 0;
            feed(s, hb ? ap.heartbeat(CUSTOM | ARMED, 20) : ap.attitude(0.2), t);
            if (hb && t < silent_from)
                last_heartbeat = t;
        }
        const auto sp = of(decode_all(s.poll(t)), "SET_ATTITUDE_TARGET");
        if (!sp.empty() && t < 8.0)
            last_setpoint = t;
        if (t > 8.2) {
            EXPECT_EQ(s.status().state, "commanding") << t;
        }
        if (t > 5.0 + 1.0 && t < 8.0) {
            EXPECT_TRUE(sp.empty()) << t;
        }
        if (t >= 8.0 && !sp.empty() && first_after < 0)
            first_after = t;
    }
    // Commands stopped within 1 s of the last heartbeat (5.0 s; telemetry until 5.0 s).
    EXPECT_EQ(last_heartbeat, 5.0);
    EXPECT_LE(last_setpoint, last_heartbeat + 1.0);
    EXPECT_GT(last_setpoint, 4.9);
    EXPECT_EQ(first_after, 8.0); // resumed with the first heartbeat back
    bool saw_lost = false;
    for (const auto& st : s.take_status())
        saw_lost = saw_lost || st.state == "lost";
    EXPECT_TRUE(saw_lost);
}

TEST(autopilot_session, foreign_systems_are_ignored)
{
    autopilot_session s(autopilot_config{});
    fake_autopilot other;
    other.sysid = 2;
    fake_autopilot gimbal;
    gimbal.compid = 154; // another component of the same system
    for (auto* ap : { &other, &gimbal }) {
        feed(s, ap->heartbeat(CUSTOM | ARMED, 15), 0.1);
        feed(s, ap->attitude(0.0), 0.1);
    }
    s.command(0.0, 0.1);
    EXPECT_TRUE(commands(decode_all(s.poll(0.1))).empty());
    EXPECT_EQ(s.status().state, "connecting");
    EXPECT_TRUE(s.take_nav().empty());
    EXPECT_EQ(s.status().foreign, 4u);
}

TEST(autopilot_session, heading_reports)
{
    autopilot_session s(autopilot_config{});
    fake_autopilot ap;
    for (double yaw : { 0.0, M_PI / 2, -M_PI / 2, 3.0 })
        feed(s, ap.attitude(yaw), 1.0);
    const auto nav = s.take_nav();
    ASSERT_EQ(nav.size(), 4u);
    EXPECT_NEAR(nav[0].heading_rad, M_PI / 2, 1e-6);                           // north
    EXPECT_NEAR(nav[1].heading_rad, 0.0, 1e-6);                                // east
    EXPECT_NEAR(std::remainder(nav[2].heading_rad - M_PI, 2 * M_PI), 0, 1e-6); // west
    EXPECT_NEAR(nav[3].heading_rad, M_PI / 2 - 3.0, 1e-6);
    EXPECT_EQ(nav[0].time, 1.0);
}

// Without GPS the autopilot's compass is magnetic: with the site's declination D (east
// of true), a reported magnetic bearing B is the true bearing B + D, and a true command
// C goes out as the magnetic C - D, by every family's command path.
TEST(autopilot_session, the_declination_turns_headings_to_true_north)
{
    const double dec = 12.8, rad = M_PI / 180;
    for (auto family : { autopilot_family::ardupilot_plane,
                         autopilot_family::ardupilot_copter,
                         autopilot_family::px4 }) {
        autopilot_config c;
        c.family = family;
        c.declination_deg = dec;
        autopilot_session s(c);
        fake_autopilot ap;
        feed(s, ap.attitude(0.0), 0.0);         // magnetic north
        feed(s, ap.attitude(-100 * rad), 0.01); // magnetic 260
        const auto nav = s.take_nav();
        ASSERT_EQ(nav.size(), 2u);
        // True bearing 12.8 deg: counter-clockwise from east, 90 - 12.8.
        EXPECT_NEAR(nav[0].heading_rad, (90 - dec) * rad, 1e-6); // ATTITUDE is float32
        EXPECT_NEAR(std::remainder(nav[1].heading_rad - (90 - 260 - dec) * rad, 2 * M_PI),
                    0,
                    1e-6);
        feed(s,
             ap.heartbeat(CUSTOM | ARMED,
                          autopilot_mode_number(family, autopilot_default_mode(family))),
             0.02);
        s.command((90 - 200) * rad, 0.02); // true bearing 200: magnetic 187.2
        double sent = NAN;
        for (double t = 0.02; t < 0.5 && std::isnan(sent); t += 0.01) {
            const auto msgs = decode_all(s.poll(t));
            for (const auto& m : commands(msgs))
                if (m.get_uint("command") == 43002) // MAV_CMD_GUIDED_CHANGE_HEADING
                    sent = m.get("param2");
            for (const auto& m : of(msgs, "SET_ATTITUDE_TARGET")) {
                const double w = m.get("q", 0), x = m.get("q", 1), y = m.get("q", 2),
                             z = m.get("q", 3);
                const double yaw =
                    std::atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z));
                sent = std::fmod(yaw / rad + 360, 360);
            }
        }
        EXPECT_NEAR(sent, 200 - dec, 1e-3) << to_string(family);
    }
    autopilot_config bad;
    for (double d : { -181.0, 181.0, double(NAN) }) {
        bad.declination_deg = d;
        EXPECT_THROW(bad.validate(), std::invalid_argument);
    }
}

TEST(autopilot_session, attitude_setpoints_for_copters)
{
    for (auto family : { autopilot_family::ardupilot_copter, autopilot_family::px4 }) {
        autopilot_config c;
        c.family = family;
        c.pitch_deg = 6;
        autopilot_session s(c);
        fake_autopilot ap;
        feed(s,
             ap.heartbeat(CUSTOM | ARMED,
                          autopilot_mode_number(family,
                                                c.family == autopilot_family::px4
                                                    ? "OFFBOARD"
                                                    : "GUIDED_NOGPS")),
             0.0);
        const double theta = -2.0; // compass 90 + 114.6 = 204.6 deg
        s.command(theta, 0.0);
        int n = 0;
        for (double t = 0.0; t < 1.0; t += 0.01) {
            if (std::fmod(t, 0.05) < 0.01)
                feed(s, ap.attitude(0), t);
            for (const auto& m : of(decode_all(s.poll(t)), "SET_ATTITUDE_TARGET")) {
                ++n;
                const double w = m.get("q", 0), x = m.get("q", 1), y = m.get("q", 2),
                             z = m.get("q", 3);
                const double yaw =
                    std::atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z));
                const double pitch = std::asin(2 * (w * y - z * x));
                const double roll =
                    std::atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y));
                EXPECT_NEAR(std::remainder(yaw - (M_PI / 2 - theta), 2 * M_PI), 0, 1e-6);
                EXPECT_NEAR(pitch, -6 * M_PI / 180, 1e-6);
                EXPECT_NEAR(roll, 0, 1e-6);
                EXPECT_FLOAT_EQ(m.get("thrust"), 0.5);
                EXPECT_EQ(m.get_uint("type_mask"), 7u);
            }
        }
        EXPECT_GE(n, 9); // 10 Hz
        EXPECT_LE(n, 11);
    }
}

TEST(autopilot_session, signed_link)
{
    std::array<std::uint8_t, 32> key;
    key.fill(0x42);
    mav::signing sign;
    sign.key = key;
    autopilot_config c;
    c.signing_key = key;
    autopilot_session s(c);
    fake_autopilot unsigned_ap, signed_ap;
    signed_ap.sign = &sign;
    feed(s, unsigned_ap.heartbeat(CUSTOM | ARMED, 15), 0.0);
    EXPECT_EQ(s.status().state, "connecting"); // unsigned: refused
    EXPECT_EQ(s.parser_stats().bad_signature, 1u);
    feed(s, signed_ap.heartbeat(CUSTOM | ARMED, 15), 0.1);
    s.command(0.0, 0.1);
    const auto frames = s.poll(0.1);
    const auto msgs = decode_all(frames, &key); // ours are signed: they verify
    EXPECT_EQ(commands(msgs).size(), 1u);
    EXPECT_EQ(s.status().state, "commanding");
}

TEST(autopilot_session, px4_setpoints_stream_before_offboard)
{
    for (auto family : { autopilot_family::px4, autopilot_family::ardupilot_copter }) {
        autopilot_config c;
        c.family = family;
        autopilot_session s(c);
        fake_autopilot ap;
        // Armed in POSCTL / ALT_HOLD (not the seeking mode), a heading commanded.
        feed(s,
             ap.heartbeat(CUSTOM | ARMED, family == autopilot_family::px4 ? 3u << 16 : 2),
             0);
        int n = 0;
        for (int k = 0; k < 100; ++k) {
            const double t = 0.01 * k;
            s.command(0.2, t);
            if (k % 5 == 0)
                feed(s, ap.attitude(0), t);
            n +=
                static_cast<int>(of(decode_all(s.poll(t)), "SET_ATTITUDE_TARGET").size());
        }
        EXPECT_EQ(s.status().state, "holding");
        if (family == autopilot_family::px4) {
            // PX4 enters OFFBOARD only with a stream already running: it runs.
            EXPECT_GE(n, 9);
            EXPECT_NE(s.status().reason.find("OFFBOARD can be entered"),
                      std::string::npos);
        } else {
            EXPECT_EQ(n, 0); // ArduCopter: nothing outside GUIDED_NOGPS
        }
    }
}

TEST(autopilot_session, a_silent_controller_or_done_stops_commands)
{
    autopilot_config c;
    c.family = autopilot_family::ardupilot_copter;
    c.command_timeout_s = 1.0;
    autopilot_session s(c);
    fake_autopilot ap;
    double last = -1;
    for (int k = 0; k <= 400; ++k) {
        const double t = 0.01 * k;
        if (t < 1.0 || (t >= 2.5 && t < 3.0))
            s.command(0.4, t); // the controller stops at 1 s, speaks again at 2.5 s
        if (t >= 3.0 && t < 3.01)
            s.finish(t);
        if (k % 5 == 0)
            feed(s, k % 100 == 0 ? ap.heartbeat(CUSTOM | ARMED, 20) : ap.attitude(0), t);
        if (!of(decode_all(s.poll(t)), "SET_ATTITUDE_TARGET").empty()) {
            last = t;
            EXPECT_TRUE(t < 2.0 + 0.11 || (t >= 2.5 && t < 3.0)) << t;
        }
        if (t > 2.1 && t < 2.5) {
            EXPECT_EQ(s.status().state, "holding");
            EXPECT_NE(s.status().reason.find("command_timeout_s"), std::string::npos);
        }
    }
    EXPECT_LT(last, 3.0);
    EXPECT_EQ(s.status().reason, "the controller is done");
    s.command(0.4, 4.1); // after done, commands are not obeyed
    EXPECT_TRUE(of(decode_all(s.poll(4.1)), "SET_ATTITUDE_TARGET").empty());
}

TEST(autopilot_session, link_details)
{
    autopilot_config c = plane_config();
    autopilot_session s(c);
    fake_autopilot ap;
    feed(s, ap.heartbeat(CUSTOM | ARMED, 15), 0.0);
    s.command(M_PI / 2 + 1e-9, 0.0); // a hair west of north: compass 359.99999994
    const auto msgs = decode_all(s.poll(0.0));
    // The streams the link needs, asked for when it comes up.
    std::vector<std::pair<double, double>> intervals;
    for (const auto& m : of(msgs, "COMMAND_LONG"))
        if (m.get_uint("command") == 511)
            intervals.emplace_back(m.get("param1"), m.get("param2"));
    EXPECT_EQ(intervals,
              (std::vector<std::pair<double, double>>{ { 30, 50000 }, { 74, 250000 } }));
    // The heading as a float in [0, 360): never 360.0.
    const auto cmds = commands(msgs);
    ASSERT_EQ(cmds.size(), 2u);
    EXPECT_EQ(cmds[1].get("param2"), 0.0);
    EXPECT_FLOAT_EQ(cmds[1].get("param3"), 6.0); // the centripetal acceleration
    // An ack addressed to another system settles nothing.
    mav::message other("COMMAND_ACK");
    other.set("command", 178);
    other.set("target_system", 255);
    feed(s, ap.frame(other), 0.05);
    EXPECT_EQ(s.status().commands_acked, 0u);
    feed(s, ap.ack(178, 0), 0.06);
    EXPECT_EQ(s.status().commands_acked, 1u);
    // Airspeed back to the autopilot's own: DO_CHANGE_SPEED with -2.
    s.set_airspeed(0);
    bool restored = false;
    for (const auto& m : commands(decode_all(s.poll(0.1))))
        restored = restored || (m.get_uint("command") == 178 && m.get("param2") == -2.0);
    EXPECT_TRUE(restored);
}

TEST(autopilot_session, signing_timestamps_never_behind_the_autopilot)
{
    std::array<std::uint8_t, 32> key;
    key.fill(7);
    mav::signing sign;
    sign.key = key;
    autopilot_config c;
    c.signing_key = key;
    c.signing_clock_offset_s = 0; // a computer whose clock says 2015
    autopilot_session s(c);
    fake_autopilot ap;
    ap.sign = &sign;
    ap.sign_time = 300000000000ull; // the autopilot's clock: 2024
    feed(s, ap.heartbeat(CUSTOM | ARMED, 15), 1.0);
    mav::parser p;
    p.require_signing(key);
    std::vector<mav::frame> out;
    for (const auto& f : s.poll(1.0))
        p.push(f.data(), f.size(), out);
    ASSERT_FALSE(out.empty());
    EXPECT_GT(out[0].timestamp, 300000000000ull);
}

namespace {
// Euler angles (roll, pitch, yaw; NED) of a SET_ATTITUDE_TARGET's quaternion.
std::array<double, 3> euler(const mav::message& m)
{
    const double w = m.get("q", 0), x = m.get("q", 1), y = m.get("q", 2),
                 z = m.get("q", 3);
    return { std::atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y)),
             std::asin(2 * (w * y - z * x)),
             std::atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z)) };
}

std::vector<std::uint8_t> vfr_hud(fake_autopilot& ap, double alt, double climb)
{
    mav::message m("VFR_HUD");
    m.set("alt", alt);
    m.set("climb", climb);
    return ap.frame(m);
}
} // namespace

// A coordinated turn: the yaw setpoint turns from where the vehicle points toward the
// command at g tan(bank) / v, banked into the turn (left, counter-clockwise: a negative
// roll) by atan(v w / g), and levels when it is there.
TEST(autopilot_session, coordinated_turns_for_multirotors)
{
    constexpr double G = 9.80665;
    autopilot_config c;
    c.family = autopilot_family::ardupilot_copter;
    c.pitch_deg = 15;
    c.turn_bank_deg = 15;
    c.turn_speed_mps = 6;
    autopilot_session s(c);
    fake_autopilot ap;
    feed(s,
         ap.heartbeat(CUSTOM | ARMED, autopilot_mode_number(c.family, "GUIDED_NOGPS")),
         0.0);
    feed(s, ap.attitude(M_PI / 2), 0.0); // pointing east: heading 0 (module)
    const double rate = G * std::tan(15 * M_PI / 180) / 6.0;
    const double target = 1.0; // 57 deg counter-clockwise: a left turn
    s.command(target, 0.0);
    double last_heading = 0.0, last_t = -1;
    bool levelled = false;
    for (double t = 0.0; t < 6.0; t += 0.01) {
        if (std::fmod(t, 0.1) < 0.01) // the autopilot keeps talking (link alive)
            feed(s,
                 ap.heartbeat(CUSTOM | ARMED,
                              autopilot_mode_number(c.family, "GUIDED_NOGPS")),
                 t);
        s.command(target, t);
        for (const auto& m : of(decode_all(s.poll(t)), "SET_ATTITUDE_TARGET")) {
            const auto [roll, pitch, yaw] = euler(m);
            const double heading = std::remainder(M_PI / 2 - yaw, 2 * M_PI);
            EXPECT_NEAR(pitch, -15 * M_PI / 180, 1e-6);
            if (last_t >= 0) {
                const double step = heading - last_heading;
                EXPECT_LE(step, rate * (t - last_t) + 1e-6);
                if (heading < target - 1e-6) { // turning: the bank of that rate
                    EXPECT_NEAR(roll, -std::atan(6.0 * step / (t - last_t) / G), 1e-4);
                    EXPECT_LT(roll, -0.2);
                } else {
                    levelled = true;
                }
            }
            if (levelled && heading >= target - 1e-6 && std::abs(roll) < 1e-9) {
                EXPECT_NEAR(heading, target, 1e-6);
            }
            last_heading = heading;
            last_t = t;
        }
    }
    EXPECT_TRUE(levelled);
    EXPECT_NEAR(last_heading, target, 1e-6);
    // 1 rad at 0.44 rad/s: about 2.3 s to turn, then level.
    EXPECT_GT(target / rate, 2.0);
}

// PX4's raw thrust: the link holds the height at which commanding began, pushing the
// thrust up when the vehicle sinks and down when it climbs.
TEST(autopilot_session, px4_holds_its_height_by_the_thrust)
{
    autopilot_config c;
    c.family = autopilot_family::px4;
    c.thrust = 0.45;
    c.hold_altitude = true;
    autopilot_session s(c);
    fake_autopilot ap;
    feed(s,
         ap.heartbeat(CUSTOM | ARMED, autopilot_mode_number(c.family, "OFFBOARD")),
         0.0);
    feed(s, vfr_hud(ap, 600.0, 0.0), 0.0);
    s.command(0.0, 0.0);
    auto thrust_at = [&](double t, double alt, double climb) {
        feed(s,
             ap.heartbeat(CUSTOM | ARMED, autopilot_mode_number(c.family, "OFFBOARD")),
             t);
        feed(s, vfr_hud(ap, alt, climb), t);
        s.command(0.0, t);
        double th = -1;
        for (const auto& m : of(decode_all(s.poll(t)), "SET_ATTITUDE_TARGET"))
            th = m.get("thrust");
        return th;
    };
    EXPECT_NEAR(thrust_at(0.2, 600.0, 0.0), 0.45, 1e-6); // at the aim: the hover thrust
    EXPECT_GT(thrust_at(0.4, 595.0, -1.0), 0.45 + 0.1);  // 5 m low and sinking
    EXPECT_LT(thrust_at(0.6, 605.0, 1.0), 0.45 - 0.05);  // 5 m high and climbing
    EXPECT_LE(thrust_at(0.8, 700.0, 5.0), 0.1 + 1e-6);   // bounded
    // Without hold_altitude the thrust is the one set.
    c.hold_altitude = false;
    autopilot_session plain(c);
    feed(plain,
         ap.heartbeat(CUSTOM | ARMED, autopilot_mode_number(c.family, "OFFBOARD")),
         0.0);
    feed(plain, vfr_hud(ap, 590.0, -1.0), 0.0);
    plain.command(0.0, 0.0);
    for (const auto& m : of(decode_all(plain.poll(0.0)), "SET_ATTITUDE_TARGET"))
        EXPECT_FLOAT_EQ(m.get("thrust"), 0.45);
}

TEST(autopilot_session, the_autopilots_clock_from_its_attitude)
{
    autopilot_session s(plane_config());
    fake_autopilot ap;
    EXPECT_FALSE(s.autopilot_time().has_value());
    mav::message m("ATTITUDE");
    m.set("time_boot_ms", 123456);
    m.set("yaw", 0.3);
    feed(s, ap.frame(m), 5.0);
    ASSERT_TRUE(s.autopilot_time().has_value());
    EXPECT_DOUBLE_EQ(*s.autopilot_time(), 123.456);
}

// The link's first seconds: heartbeats alone (the streams not yet flowing) do not make
// the link lost; once the streams flow, their silence does.
TEST(autopilot_session, heartbeats_alone_do_not_lose_a_new_link)
{
    autopilot_session s(plane_config());
    fake_autopilot ap;
    const auto guided =
        autopilot_mode_number(autopilot_family::ardupilot_plane, "GUIDED");
    for (double t = 0.0; t < 3.0; t += 0.01) {
        if (std::fmod(t + 1e-9, 1.0) < 0.01)
            feed(s, ap.heartbeat(CUSTOM | ARMED, guided), t);
        s.poll(t);
        EXPECT_NE(s.status().state, "lost") << "at " << t;
    }
    for (double t = 3.0; t < 3.5; t += 0.05) { // the streams begin
        feed(s, ap.attitude(0.1), t);
        s.poll(t);
    }
    EXPECT_NE(s.status().state, "lost");
    s.poll(3.45 + 0.5 + 0.1); // link_timeout_s (0.5 s) after the last frame
    EXPECT_EQ(s.status().state, "lost");
    // Heartbeats alone for longer than the grace (heartbeat_timeout_s, 3.5 s): lost.
    autopilot_session quiet(plane_config());
    bool lost = false;
    for (double t = 0.0; t < 6.0; t += 0.01) {
        if (std::fmod(t + 1e-9, 1.0) < 0.01)
            feed(quiet, ap.heartbeat(CUSTOM | ARMED, guided), t);
        quiet.poll(t);
        if (quiet.status().state == "lost") {
            EXPECT_GT(t, 3.5);
            lost = true;
        }
    }
    EXPECT_TRUE(lost);
}
