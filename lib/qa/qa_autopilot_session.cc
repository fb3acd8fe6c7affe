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
    EXPECT_TRUE(of(decode_all(s.poll(0.1)), "COMMAND_LONG").empty());
    EXPECT_EQ(s.status().state, "holding");
    EXPECT_EQ(s.status().reason, "not armed");

    feed(s, ap.heartbeat(CUSTOM | ARMED, 5), 0.2); // armed, FBWA
    EXPECT_TRUE(of(decode_all(s.poll(0.2)), "COMMAND_LONG").empty());
    EXPECT_EQ(s.status().state, "holding");
    EXPECT_NE(s.status().reason.find("not GUIDED"), std::string::npos);

    feed(s, ap.heartbeat(CUSTOM | ARMED, 15), 0.3); // armed, GUIDED
    const auto cmds = of(decode_all(s.poll(0.3)), "COMMAND_LONG");
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
    EXPECT_TRUE(of(decode_all(s.poll(0.5)), "COMMAND_LONG").empty());
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
    auto cmds = of(decode_all(s.poll(0.0)), "COMMAND_LONG");
    ASSERT_EQ(cmds.size(), 1u); // no airspeed set: no DO_CHANGE_SPEED
    EXPECT_FLOAT_EQ(cmds[0].get("param2"), 0.0);
    feed(s, ap.ack(43002, 0), 0.05);
    // Within the deadband: not sent again. Beyond it, but too soon: waits for
    // command_min_period_s.
    feed(s, ap.attitude(0), 0.1);
    s.command(M_PI / 2 - 0.5 * M_PI / 180, 0.1);
    EXPECT_TRUE(of(decode_all(s.poll(0.1)), "COMMAND_LONG").empty());
    s.command(M_PI / 2 - 20 * M_PI / 180, 0.15); // 20 deg right: compass 20
    feed(s, ap.attitude(0), 0.15);
    EXPECT_TRUE(of(decode_all(s.poll(0.15)), "COMMAND_LONG").empty());
    feed(s, ap.attitude(0), 0.2);
    cmds = of(decode_all(s.poll(0.2)), "COMMAND_LONG");
    ASSERT_EQ(cmds.size(), 1u);
    EXPECT_NEAR(cmds[0].get("param2"), 20.0, 1e-4);
}

TEST(autopilot_session, unanswered_commands_are_retried_then_fail)
{
    autopilot_config c;
    c.ack_timeout_s = 0.3;
    c.retries = 3;
    autopilot_session s(c);
    fake_autopilot ap;
    s.command(0.0, 0.0);
    std::vector<double> sent_at;
    std::vector<std::uint64_t> confirmations;
    for (int k = 0; k <= 200; ++k) {
        const double t = 0.01 * k;
        if (k % 5 == 0) // telemetry at 20 Hz, heartbeats at 1 Hz
            feed(
                s, k % 100 == 0 ? ap.heartbeat(CUSTOM | ARMED, 15) : ap.attitude(1.0), t);
        for (const auto& m : of(decode_all(s.poll(t)), "COMMAND_LONG")) {
            sent_at.push_back(t);
            confirmations.push_back(m.get_uint("confirmation"));
        }
    }
    // First send, then 3 retries 0.3 s apart with confirmation 1, 2, 3; then failure,
    // and no new send of the same heading.
    ASSERT_EQ(sent_at.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_NEAR(sent_at[i], 0.3 * i, 0.011);
        EXPECT_EQ(confirmations[i], i);
    }
    EXPECT_EQ(s.status().retries, 3u);
    EXPECT_EQ(s.status().commands_failed, 1u);
    EXPECT_NE(s.status().reason.find("no ack after 4 sends"), std::string::npos);

    // Refused: no retry; the reason names the result.
    autopilot_session r(c);
    fake_autopilot ap2;
    feed(r, ap2.heartbeat(CUSTOM | ARMED, 15), 0.0);
    r.command(0.0, 0.0);
    EXPECT_EQ(of(decode_all(r.poll(0.0)), "COMMAND_LONG").size(), 1u);
    feed(r, ap2.ack(43002, 2), 0.1); // DENIED
    EXPECT_EQ(r.status().commands_failed, 1u);
    EXPECT_NE(r.status().reason.find("DENIED"), std::string::npos);
    // A temporarily rejected command is sent again at its timeout; accepted, it stops.
    r.command(0.5, 0.2);
    feed(r, ap2.attitude(0), 0.2);
    EXPECT_EQ(of(decode_all(r.poll(0.2)), "COMMAND_LONG").size(), 1u);
    feed(r, ap2.ack(43002, 1), 0.25);
    feed(r, ap2.attitude(0), 0.45);
    EXPECT_TRUE(of(decode_all(r.poll(0.45)), "COMMAND_LONG").empty());
    feed(r, ap2.attitude(0), 0.5);
    EXPECT_EQ(of(decode_all(r.poll(0.5)), "COMMAND_LONG").size(), 1u);
    feed(r, ap2.ack(43002, 0), 0.55);
    for (double t = 0.6; t < 1.5; t += 0.05) {
        feed(r, ap2.attitude(0), t);
        EXPECT_TRUE(of(decode_all(r.poll(t)), "COMMAND_LONG").empty()) << t;
    }
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
    EXPECT_TRUE(of(decode_all(s.poll(0.1)), "COMMAND_LONG").empty());
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
    EXPECT_EQ(of(msgs, "COMMAND_LONG").size(), 1u);
    EXPECT_EQ(s.status().state, "commanding");
}
