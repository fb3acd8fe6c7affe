/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The MAVLink codec (include/gr-rfseek/mavlink.h): known answers (the CRC catalogue's
 * check value, the CRC_EXTRA values the MAVLink documentation lists, a frame laid out by
 * hand with an independent bitwise CRC), truncation, MAVLink 1, signing and replay rules,
 * and the parser's resynchronisation. The cross-check against node-mavlink, an
 * independent implementation, is lib/qa/mavlink_crosscheck.js.
 */

#include <gr-rfseek/mavlink.h>
#include <gtest/gtest.h>
#include <cmath>
#include <map>
#include <string>

using namespace gr::rfseek::mavlink;

namespace {

// CRC-16/MCRF4XX bit by bit (reflected polynomial 0x8408, initial 0xFFFF, no final
// XOR): written from the catalogue's definition, not from the codec's byte-wise form.
std::uint16_t crc_bitwise(const std::vector<std::uint8_t>& data)
{
    std::uint16_t crc = 0xFFFF;
    for (std::uint8_t b : data) {
        crc ^= b;
        for (int k = 0; k < 8; ++k)
            crc = (crc & 1) ? static_cast<std::uint16_t>((crc >> 1) ^ 0x8408)
                            : static_cast<std::uint16_t>(crc >> 1);
    }
    return crc;
}

std::vector<frame> parse_all(parser& p, const std::vector<std::uint8_t>& bytes)
{
    std::vector<frame> out;
    p.push(bytes.data(), bytes.size(), out);
    return out;
}

message heartbeat(std::uint32_t custom_mode)
{
    message hb("HEARTBEAT");
    hb.set("type", 1);      // MAV_TYPE_FIXED_WING
    hb.set("autopilot", 3); // MAV_AUTOPILOT_ARDUPILOTMEGA
    hb.set("base_mode", 0x81);
    hb.set("custom_mode", custom_mode);
    hb.set("system_status", 4);
    hb.set("mavlink_version", 3);
    return hb;
}

} // namespace

TEST(mavlink, crc_check_value)
{
    // The CRC catalogue's check value of CRC-16/MCRF4XX over "123456789".
    const std::string s = "123456789";
    EXPECT_EQ(crc_x25(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()), 0x6F91);
    EXPECT_EQ(crc_bitwise(std::vector<std::uint8_t>(s.begin(), s.end())), 0x6F91);
}

TEST(mavlink, crc_extra_as_documented)
{
    // CRC_EXTRA as the MAVLink message documentation lists them.
    const std::map<std::string, int> documented = { { "HEARTBEAT", 50 },
                                                    { "SYS_STATUS", 124 },
                                                    { "SET_MODE", 89 },
                                                    { "ATTITUDE", 39 },
                                                    { "GLOBAL_POSITION_INT", 104 },
                                                    { "VFR_HUD", 20 },
                                                    { "COMMAND_INT", 158 },
                                                    { "COMMAND_LONG", 152 },
                                                    { "COMMAND_ACK", 143 },
                                                    { "SET_ATTITUDE_TARGET", 49 },
                                                    { "ATTITUDE_TARGET", 22 },
                                                    { "SET_POSITION_TARGET_LOCAL_NED",
                                                      143 },
                                                    { "POSITION_TARGET_LOCAL_NED", 140 },
                                                    { "STATUSTEXT", 83 },
                                                    { "SIM_STATE", 32 },
                                                    { "HIL_STATE_QUATERNION", 4 },
                                                    { "SYSTEM_TIME", 137 },
                                                    { "PARAM_SET", 168 },
                                                    { "PARAM_VALUE", 220 },
                                                    { "RC_CHANNELS_OVERRIDE", 124 } };
    EXPECT_EQ(definitions().size(), documented.size());
    for (const auto& kv : documented) {
        const message_def* d = find_message(kv.first);
        ASSERT_NE(d, nullptr) << kv.first;
        EXPECT_EQ(d->crc_extra, kv.second) << kv.first;
        // Recomputed from the field table: the wire order and types are right.
        EXPECT_EQ(compute_crc_extra(*d), kv.second) << kv.first;
        ASSERT_NE(find_frame(d->id), nullptr);
        EXPECT_EQ(find_frame(d->id)->crc_extra, kv.second) << kv.first;
        EXPECT_EQ(find_frame(d->id)->base_len, d->base_len) << kv.first;
        EXPECT_EQ(find_frame(d->id)->max_len, d->max_len) << kv.first;
    }
    // Payload lengths as documented (without / with extensions).
    EXPECT_EQ(find_message("HEARTBEAT")->base_len, 9u);
    EXPECT_EQ(find_message("SYS_STATUS")->base_len, 31u);
    EXPECT_EQ(find_message("SYS_STATUS")->max_len, 43u);
    EXPECT_EQ(find_message("COMMAND_LONG")->base_len, 33u);
    EXPECT_EQ(find_message("STATUSTEXT")->base_len, 51u);
    EXPECT_EQ(find_message("STATUSTEXT")->max_len, 54u);
    EXPECT_EQ(find_message(999999u), nullptr);
    EXPECT_EQ(find_frame(24)->crc_extra, 24); // GPS_RAW_INT: in the dialect, not decoded
}

TEST(mavlink, heartbeat_frame_by_hand)
{
    const message hb = heartbeat(0x0A0B0C0D);
    const auto f = encode(hb, header{ 7, 42, 1 });
    // Laid out by hand: magic, len, flags, seq, sys, comp, id (3 bytes), payload in
    // wire order (custom_mode little endian, then the uint8 fields), CRC.
    std::vector<std::uint8_t> expect = { 0xFD, 9,    0,    0,    7, 42, 1,    0, 0, 0,
                                         0x0D, 0x0C, 0x0B, 0x0A, 1, 3,  0x81, 4, 3 };
    std::vector<std::uint8_t> crc_input(expect.begin() + 1, expect.end());
    crc_input.push_back(50); // CRC_EXTRA of HEARTBEAT
    const std::uint16_t crc = crc_bitwise(crc_input);
    expect.push_back(crc & 0xFF);
    expect.push_back(crc >> 8);
    EXPECT_EQ(f, expect);

    parser p;
    const auto out = parse_all(p, f);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].hdr.seq, 7);
    EXPECT_EQ(out[0].hdr.sysid, 42);
    EXPECT_EQ(out[0].raw, f);
    EXPECT_TRUE(out[0].decode() == hb);
    EXPECT_EQ(out[0].decode().get_uint("custom_mode"), 0x0A0B0C0Du);
}

TEST(mavlink, truncation_and_v1)
{
    message cmd("COMMAND_LONG");
    cmd.set("param1", 1.5);
    cmd.set("command", 43002); // MAV_CMD_GUIDED_CHANGE_HEADING
    cmd.set("target_system", 1);
    // Wire order: 7 floats (28 bytes), command (2), target_system, target_component,
    // confirmation: the trailing zeros (target_component, confirmation) are cut.
    auto f = encode(cmd, header{});
    EXPECT_EQ(f[1], 31);
    // An all-zero payload keeps its first byte.
    message zero("COMMAND_ACK");
    EXPECT_EQ(encode(zero, header{})[1], 1);
    // A v2 frame whose sender did not truncate still decodes.
    message ack("COMMAND_ACK");
    ack.set("command", 176);
    ack.set("result", 0);
    parser p;
    auto v2 = encode(ack, header{ 1, 1, 1 });
    auto v1 = encode_v1(ack, header{ 2, 1, 1 });
    EXPECT_EQ(v1[0], 0xFE);
    EXPECT_EQ(v1[1], find_message("COMMAND_ACK")->base_len);
    std::vector<std::uint8_t> stream = v2;
    stream.insert(stream.end(), v1.begin(), v1.end());
    stream.insert(stream.end(), f.begin(), f.end());
    const auto out = parse_all(p, stream);
    ASSERT_EQ(out.size(), 3u);
    EXPECT_EQ(out[0].version, 2);
    EXPECT_EQ(out[1].version, 1);
    EXPECT_TRUE(out[0].decode() == ack);
    EXPECT_TRUE(out[1].decode() == ack);
    EXPECT_TRUE(out[2].decode() == cmd);
    EXPECT_EQ(out[2].decode().get("param1"), 1.5);
}

TEST(mavlink, field_access)
{
    message m("ATTITUDE_TARGET");
    m.set("q", 0.5, 3);
    EXPECT_EQ(m.get("q", 3), 0.5);
    EXPECT_THROW(m.get("q", 4), std::out_of_range);
    EXPECT_THROW(m.set("no_such_field", 1), std::invalid_argument);
    message s("SYS_STATUS");
    s.set("battery_remaining", -200); // int8: clamped
    EXPECT_EQ(s.get_int("battery_remaining"), -128);
    s.set("load", 1e9); // uint16: clamped
    EXPECT_EQ(s.get_uint("load"), 65535u);
    s.set("load", std::nan(""));
    EXPECT_EQ(s.get_uint("load"), 0u);
    s.set("current_battery", -12.7); // toward zero
    EXPECT_EQ(s.get_int("current_battery"), -12);
    message t("STATUSTEXT");
    t.set_text("text", std::string(60, 'x'));
    EXPECT_EQ(t.get_text("text"), std::string(50, 'x'));
    t.set_text("text", "rfseek");
    EXPECT_EQ(t.get_text("text"), "rfseek");
    EXPECT_THROW(message("NO_SUCH_MESSAGE"), std::invalid_argument);
}

TEST(mavlink, signing_and_replay)
{
    signing sign;
    for (std::size_t i = 0; i < sign.key.size(); ++i)
        sign.key[i] = static_cast<std::uint8_t>(3 * i + 1);
    sign.link_id = 4;
    const message hb = heartbeat(15);
    const auto a = encode(hb, header{ 0, 1, 1 }, &sign, 1000);
    const auto b = encode(hb, header{ 1, 1, 1 }, &sign, 1001);
    EXPECT_EQ(a.size(), 10u + 9u + 2u + 13u);
    EXPECT_EQ(a[2], 0x01); // the signed flag
    EXPECT_EQ(a[21], 4);   // link id

    parser p;
    p.require_signing(sign.key);
    auto out = parse_all(p, a);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_TRUE(out[0].is_signed);
    EXPECT_EQ(out[0].timestamp, 1000u);
    EXPECT_EQ(out[0].link_id, 4);
    // The same frame again: replayed. The next timestamp: accepted.
    EXPECT_TRUE(parse_all(p, a).empty());
    EXPECT_EQ(p.stats().replayed, 1u);
    EXPECT_EQ(parse_all(p, b).size(), 1u);
    // Unsigned: refused when signing is required.
    EXPECT_TRUE(parse_all(p, encode(hb, header{})).empty());
    EXPECT_EQ(p.stats().bad_signature, 1u);
    // Another key: refused.
    signing other = sign;
    other.key[0] ^= 1;
    EXPECT_TRUE(parse_all(p, encode(hb, header{ 2, 1, 1 }, &other, 2000)).empty());
    EXPECT_EQ(p.stats().bad_signature, 2u);
    // A tampered payload byte with the CRC made right again still fails the signature.
    auto c = encode(hb, header{ 3, 1, 1 }, &sign, 3000);
    c[10] ^= 0xFF;
    std::vector<std::uint8_t> body(c.begin() + 1, c.begin() + 19);
    body.push_back(50);
    const std::uint16_t crc = crc_bitwise(body);
    c[19] = crc & 0xFF;
    c[20] = crc >> 8;
    EXPECT_TRUE(parse_all(p, c).empty());
    EXPECT_EQ(p.stats().bad_signature, 3u);
    // A new stream (another component) more than a minute older than the newest: refused;
    // within the minute: accepted.
    EXPECT_TRUE(parse_all(p, encode(hb, header{ 0, 1, 2 }, &sign, 1001 + 1)).size() ==
                1u);
    parser q;
    q.require_signing(sign.key);
    EXPECT_EQ(parse_all(q, encode(hb, header{ 0, 1, 1 }, &sign, 10000000)).size(), 1u);
    EXPECT_TRUE(parse_all(q, encode(hb, header{ 0, 1, 3 }, &sign, 3000000)).empty());
    EXPECT_EQ(q.stats().replayed, 1u);
    EXPECT_EQ(parse_all(q, encode(hb, header{ 0, 1, 4 }, &sign, 9000000)).size(), 1u);
    // Unsigned accepted when asked.
    parser r;
    r.require_signing(sign.key, true);
    EXPECT_EQ(parse_all(r, encode(hb, header{})).size(), 1u);
}

TEST(mavlink, parser_resynchronises)
{
    const message hb = heartbeat(9);
    const auto good = encode(hb, header{ 5, 1, 1 });
    auto bad = good;
    bad[12] ^= 0x10; // a payload bit: the CRC fails
    // A frame of the dialect the codec does not decode (GPS_RAW_INT, id 24): checked
    // with its CRC_EXTRA and returned undecoded.
    std::vector<std::uint8_t> gps = { 0xFD, 1, 0, 0, 9, 1, 1, 24, 0, 0, 0x2A };
    std::vector<std::uint8_t> crc_in(gps.begin() + 1, gps.end());
    crc_in.push_back(find_frame(24)->crc_extra);
    const std::uint16_t crc = crc_bitwise(crc_in);
    gps.push_back(crc & 0xFF);
    gps.push_back(crc >> 8);
    // An id outside the dialect.
    std::vector<std::uint8_t> alien = {
        0xFD, 1, 0, 0, 9, 1, 1, 0x33, 0x22, 0x11, 0, 0, 0
    };

    std::vector<std::uint8_t> stream = { 0x00, 0xFD, 0x55, 0xFE };
    for (const std::vector<std::uint8_t>* part :
         std::initializer_list<const std::vector<std::uint8_t>*>{
             &bad, &good, &gps, &alien, &good })
        stream.insert(stream.end(), part->begin(), part->end());
    // Byte by byte and all at once: the same frames.
    parser whole, bytewise;
    const auto a = parse_all(whole, stream);
    std::vector<frame> b;
    for (std::uint8_t x : stream)
        bytewise.push(&x, 1, b);
    for (const std::vector<frame>* out :
         std::initializer_list<const std::vector<frame>*>{ &a, &b }) {
        ASSERT_EQ(out->size(), 3u);
        EXPECT_TRUE((*out)[0].decode() == hb);
        EXPECT_FALSE((*out)[1].known());
        EXPECT_EQ((*out)[1].msgid, 24u);
        EXPECT_THROW((*out)[1].decode(), std::invalid_argument);
        EXPECT_TRUE((*out)[2].decode() == hb);
    }
    EXPECT_GE(whole.stats().bad_crc, 1u);
    EXPECT_GE(whole.stats().unknown, 1u);
    EXPECT_EQ(whole.stats().undecoded, 1u);
    EXPECT_EQ(whole.stats().frames, 3u);
    EXPECT_EQ(bytewise.stats().frames, 3u);
}
