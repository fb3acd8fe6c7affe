/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rfseek_mavlink_tool: the module's side of the cross-check of its MAVLink codec
 * against node-mavlink (lib/qa/mavlink_crosscheck.js drives it; test-only).
 *
 *   rfseek_mavlink_tool encode SEED COUNT KEYHEX
 *       COUNT seeded random messages of every type the codec decodes, one JSON line
 *       each: the fields set, the header, the signing (a third of the v2 frames), and
 *       the frame our encoder wrote (a tenth are MAVLink 1 frames).
 *   rfseek_mavlink_tool decode KEYHEX
 *       Hex frames on stdin (one per line) through one parser that checks signatures
 *       with KEYHEX (unsigned frames accepted): one JSON line per input line, the
 *       decoded frame or the counters that rose (why it was refused).
 *   rfseek_mavlink_tool types
 *       The decoded message types (fields, CRC_EXTRA) and the CRC_EXTRA of every
 *       message of the dialect table.
 */

#include <gr-rfseek/mavlink.h>
#include <nlohmann/json.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <random>
#include <string>

using namespace gr::rfseek::mavlink;
using json = nlohmann::json;

namespace {

std::array<std::uint8_t, 32> parse_key(const std::string& hex)
{
    std::array<std::uint8_t, 32> key{};
    if (hex.size() != 64)
        throw std::invalid_argument("KEYHEX: 64 hex digits (a 32-byte key)");
    for (std::size_t i = 0; i < 32; ++i)
        key[i] = static_cast<std::uint8_t>(std::stoul(hex.substr(2 * i, 2), nullptr, 16));
    return key;
}

std::string to_hex(const std::vector<std::uint8_t>& b)
{
    static const char* digits = "0123456789abcdef";
    std::string s;
    for (std::uint8_t x : b) {
        s += digits[x >> 4];
        s += digits[x & 15];
    }
    return s;
}

std::vector<std::uint8_t> from_hex(const std::string& s)
{
    std::vector<std::uint8_t> b;
    for (std::size_t i = 0; i + 1 < s.size(); i += 2)
        b.push_back(static_cast<std::uint8_t>(std::stoul(s.substr(i, 2), nullptr, 16)));
    return b;
}

// A field's element as JSON: 64-bit integers as decimal strings (exact in JavaScript
// as BigInt), floats as the double the float32 widens to (exact).
json element(const message& m, const field_def& f, std::size_t i)
{
    switch (f.type) {
    case ftype::u64:
        return std::to_string(m.get_uint(f.name, i));
    case ftype::i64:
        return std::to_string(m.get_int(f.name, i));
    case ftype::f32:
    case ftype::f64:
        return m.get(f.name, i);
    default:
        return m.get_int(f.name, i) < 0 ? json(m.get_int(f.name, i))
                                        : json(m.get_uint(f.name, i));
    }
}

json fields_of(const message& m)
{
    json out = json::object();
    for (const field_def& f : m.def().fields) {
        if (f.type == ftype::chr) {
            out[f.name] = m.get_text(f.name);
        } else if (f.count) {
            json a = json::array();
            for (std::size_t i = 0; i < f.count; ++i)
                a.push_back(element(m, f, i));
            out[f.name] = a;
        } else {
            out[f.name] = element(m, f, 0);
        }
    }
    return out;
}

// A random finite float32: random sign, mantissa and a moderate exponent; a third of
// the values are zero (so that payloads truncate).
float random_float(std::mt19937_64& rng)
{
    if (rng() % 3 == 0)
        return 0.0f;
    const std::uint32_t sign = static_cast<std::uint32_t>(rng() & 1) << 31;
    const std::uint32_t exponent = static_cast<std::uint32_t>(127 - 30 + rng() % 60)
                                   << 23;
    const std::uint32_t mantissa = static_cast<std::uint32_t>(rng()) & 0x7FFFFF;
    const std::uint32_t bits = sign | exponent | mantissa;
    float x;
    std::memcpy(&x, &bits, 4);
    return x;
}

void randomise(message& m, std::mt19937_64& rng)
{
    for (const field_def& f : m.def().fields) {
        if (f.type == ftype::chr) {
            std::string text(rng() % (f.count + 1), ' ');
            for (char& c : text)
                c = static_cast<char>(32 + rng() % 95);
            m.set_text(f.name, text);
            continue;
        }
        for (std::size_t i = 0; i < f.elements(); ++i) {
            if (f.type == ftype::f32)
                m.set(f.name, random_float(rng), i);
            else if (f.type == ftype::f64)
                m.set(f.name, static_cast<double>(random_float(rng)) * 1.000001, i);
            else if (rng() % 3 == 0)
                m.set_uint(f.name, 0, i);
            else
                m.set_uint(f.name, rng(), i); // cut to the field's width
        }
    }
}

int encode_cmd(std::uint64_t seed, std::size_t count, const std::string& keyhex)
{
    std::mt19937_64 rng(seed);
    signing sign;
    sign.key = parse_key(keyhex);
    std::vector<std::uint32_t> ids;
    for (const auto& kv : definitions())
        ids.push_back(kv.first);
    std::uint64_t timestamp = 100000000;
    for (std::size_t n = 0; n < count; ++n) {
        message m(ids[n % ids.size()]);
        randomise(m, rng);
        header h{ static_cast<std::uint8_t>(n),
                  static_cast<std::uint8_t>(1 + rng() % 255),
                  static_cast<std::uint8_t>(1 + rng() % 255) };
        const bool v1 = rng() % 10 == 0;
        const bool is_signed = !v1 && rng() % 3 == 0;
        sign.link_id = static_cast<std::uint8_t>(rng());
        timestamp += 1 + rng() % 1000;
        json line;
        line["name"] = m.def().name;
        line["id"] = m.id();
        line["version"] = v1 ? 1 : 2;
        line["seq"] = h.seq;
        line["sysid"] = h.sysid;
        line["compid"] = h.compid;
        line["signed"] = is_signed;
        if (is_signed) {
            line["link_id"] = sign.link_id;
            line["timestamp"] = timestamp;
        }
        if (v1) {
            // A MAVLink 1 frame has no extension fields: they read back as zero.
            for (const field_def& f : m.def().fields)
                if (f.extension)
                    for (std::size_t i = 0; i < f.elements(); ++i)
                        f.type == ftype::chr ? m.set_text(f.name, "")
                                             : m.set_uint(f.name, 0, i);
        }
        line["fields"] = fields_of(m);
        line["frame"] = to_hex(v1 ? encode_v1(m, h)
                                  : encode(m, h, is_signed ? &sign : nullptr, timestamp));
        std::cout << line.dump() << '\n';
    }
    return 0;
}

int decode_cmd(const std::string& keyhex)
{
    parser p;
    p.require_signing(parse_key(keyhex), true);
    std::string hex;
    while (std::getline(std::cin, hex)) {
        const auto bytes = from_hex(hex);
        const parser::counters before = p.stats();
        std::vector<frame> out;
        p.push(bytes.data(), bytes.size(), out);
        const parser::counters& after = p.stats();
        json line;
        line["bad_crc"] = after.bad_crc - before.bad_crc;
        line["unknown"] = after.unknown - before.unknown;
        line["bad_signature"] = after.bad_signature - before.bad_signature;
        line["replayed"] = after.replayed - before.replayed;
        line["frames"] = json::array();
        for (const frame& f : out) {
            json j;
            j["version"] = f.version;
            j["id"] = f.msgid;
            j["seq"] = f.hdr.seq;
            j["sysid"] = f.hdr.sysid;
            j["compid"] = f.hdr.compid;
            j["signed"] = f.is_signed;
            j["link_id"] = f.link_id;
            j["timestamp"] = f.timestamp;
            if (f.known()) {
                const message m = f.decode();
                j["name"] = m.def().name;
                j["fields"] = fields_of(m);
            }
            line["frames"].push_back(j);
        }
        std::cout << line.dump() << '\n';
    }
    return 0;
}

int types_cmd()
{
    json messages = json::array();
    for (const auto& kv : definitions()) {
        json fields = json::array();
        for (const field_def& f : kv.second.fields)
            fields.push_back({ { "name", f.name },
                               { "type", type_name(f.type) },
                               { "count", f.count },
                               { "extension", f.extension } });
        messages.push_back({ { "id", kv.first },
                             { "name", kv.second.name },
                             { "crc_extra", kv.second.crc_extra },
                             { "fields", fields } });
    }
    json frames = json::array(); // every id of the dialect table (all below 2^16)
    for (std::uint32_t id = 0; id < 65536; ++id)
        if (const frame_info* f = find_frame(id))
            frames.push_back({ id, f->crc_extra });
    std::cout << json{ { "messages", messages }, { "frames", frames } }.dump() << '\n';
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    try {
        const std::string cmd = argc > 1 ? argv[1] : "";
        if (cmd == "encode" && argc == 5)
            return encode_cmd(std::stoull(argv[2]), std::stoul(argv[3]), argv[4]);
        if (cmd == "decode" && argc == 3)
            return decode_cmd(argv[2]);
        if (cmd == "types" && argc == 2)
            return types_cmd();
    } catch (const std::exception& e) {
        std::cerr << "rfseek_mavlink_tool: " << e.what() << '\n';
        return 1;
    }
    std::cerr << "usage: rfseek_mavlink_tool encode SEED COUNT KEYHEX | decode KEYHEX | "
                 "types\n";
    return 2;
}
