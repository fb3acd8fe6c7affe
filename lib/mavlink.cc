/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include <gr-rfseek/mavlink.h>
#include <openssl/evp.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>

namespace gr {
namespace rfseek {
namespace mavlink {

namespace {

constexpr std::uint8_t MAGIC_V1 = 0xFE, MAGIC_V2 = 0xFD;
constexpr std::uint8_t IFLAG_SIGNED = 0x01;
constexpr std::size_t V1_HEADER = 6, V2_HEADER = 10, SIGNATURE = 13;

struct raw_field {
    const char* name;
    ftype type;
    std::size_t count;
    bool extension;
};

message_def make_def(std::uint32_t id,
                     const char* name,
                     std::uint8_t crc_extra,
                     std::initializer_list<raw_field> fields)
{
    message_def d;
    d.id = id;
    d.name = name;
    d.crc_extra = crc_extra;
    std::size_t offset = 0;
    for (const raw_field& f : fields) {
        field_def fd{ f.name, f.type, f.count, f.extension, offset };
        offset += fd.bytes();
        if (!f.extension)
            d.base_len = offset;
        d.fields.push_back(fd);
    }
    d.max_len = offset;
    return d;
}

std::map<std::uint32_t, message_def> build_definitions()
{
    std::map<std::uint32_t, message_def> m;
#define RFSEEK_MAVLINK_MESSAGE(id, name, crc, ...) \
    m.emplace(id, make_def(id, #name, crc, { __VA_ARGS__ }));
#include "mavlink_tables.inc"
#undef RFSEEK_MAVLINK_MESSAGE
    return m;
}

std::map<std::uint32_t, frame_info> build_frames()
{
    std::map<std::uint32_t, frame_info> m;
#define RFSEEK_MAVLINK_FRAME(id, crc, base, max) \
    m.emplace(id, frame_info{ id, crc, base, max });
#include "mavlink_tables.inc"
#undef RFSEEK_MAVLINK_FRAME
    return m;
}

void put_le(std::uint8_t* p, std::uint64_t v, std::size_t n)
{
    for (std::size_t i = 0; i < n; ++i)
        p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

std::uint64_t get_le(const std::uint8_t* p, std::size_t n)
{
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i)
        v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
    return v;
}

bool is_signed_type(ftype t)
{
    return t == ftype::i8 || t == ftype::i16 || t == ftype::i32 || t == ftype::i64;
}

// The 6 bytes of a frame's signature: SHA-256 over the key and the frame up to and
// including the link id and timestamp, first 48 bits.
std::array<std::uint8_t, 6> signature_of(const std::array<std::uint8_t, 32>& key,
                                         const std::uint8_t* frame_bytes,
                                         std::size_t n)
{
    std::uint8_t digest[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    const std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx(EVP_MD_CTX_new(),
                                                                 EVP_MD_CTX_free);
    if (!ctx || !EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) ||
        !EVP_DigestUpdate(ctx.get(), key.data(), key.size()) ||
        !EVP_DigestUpdate(ctx.get(), frame_bytes, n) ||
        !EVP_DigestFinal_ex(ctx.get(), digest, &len) || len < 6)
        throw std::runtime_error("mavlink signing: SHA-256 failed (OpenSSL)");
    std::array<std::uint8_t, 6> s;
    std::copy(digest, digest + 6, s.begin());
    return s;
}

} // namespace

std::size_t size_of(ftype t)
{
    switch (t) {
    case ftype::u8:
    case ftype::i8:
    case ftype::chr:
        return 1;
    case ftype::u16:
    case ftype::i16:
        return 2;
    case ftype::u32:
    case ftype::i32:
    case ftype::f32:
        return 4;
    default:
        return 8;
    }
}

const char* type_name(ftype t)
{
    static const char* names[] = { "uint8_t",  "int8_t",  "uint16_t", "int16_t",
                                   "uint32_t", "int32_t", "uint64_t", "int64_t",
                                   "float",    "double",  "char" };
    return names[static_cast<int>(t)];
}

const field_def* message_def::field(const std::string& n) const
{
    for (const field_def& f : fields)
        if (f.name == n)
            return &f;
    return nullptr;
}

const frame_info* find_frame(std::uint32_t id)
{
    static const std::map<std::uint32_t, frame_info> frames = build_frames();
    const auto it = frames.find(id);
    return it == frames.end() ? nullptr : &it->second;
}

const std::map<std::uint32_t, message_def>& definitions()
{
    static const std::map<std::uint32_t, message_def> defs = build_definitions();
    return defs;
}

const message_def* find_message(std::uint32_t id)
{
    const auto& d = definitions();
    const auto it = d.find(id);
    return it == d.end() ? nullptr : &it->second;
}

const message_def* find_message(const std::string& name)
{
    for (const auto& kv : definitions())
        if (kv.second.name == name)
            return &kv.second;
    return nullptr;
}

std::uint16_t crc_x25(const std::uint8_t* data, std::size_t n, std::uint16_t crc)
{
    for (std::size_t i = 0; i < n; ++i) {
        std::uint8_t t = data[i] ^ static_cast<std::uint8_t>(crc & 0xFF);
        t ^= static_cast<std::uint8_t>(t << 4);
        crc = static_cast<std::uint16_t>((crc >> 8) ^ (t << 8) ^ (t << 3) ^ (t >> 4));
    }
    return crc;
}

std::uint8_t compute_crc_extra(const message_def& d)
{
    auto add = [](const std::string& s, std::uint16_t crc) {
        return crc_x25(reinterpret_cast<const std::uint8_t*>(s.data()), s.size(), crc);
    };
    std::uint16_t crc = add(d.name + " ", 0xFFFF);
    for (const field_def& f : d.fields) {
        if (f.extension)
            break;
        crc = add(std::string(type_name(f.type)) + " ", crc);
        crc = add(f.name + " ", crc);
        if (f.count) {
            const std::uint8_t c = static_cast<std::uint8_t>(f.count);
            crc = crc_x25(&c, 1, crc);
        }
    }
    return static_cast<std::uint8_t>((crc & 0xFF) ^ (crc >> 8));
}

// --- message --------------------------------------------------------------------

message::message(const std::string& name) : d_def(find_message(name))
{
    if (!d_def)
        throw std::invalid_argument("mavlink message '" + name + "': not one the codec " +
                                    "knows (lib/mavlink_tables.inc)");
    d_payload.assign(d_def->max_len, 0);
}

message::message(std::uint32_t id) : d_def(find_message(id))
{
    if (!d_def)
        throw std::invalid_argument("mavlink message id " + std::to_string(id) +
                                    ": not one the codec knows");
    d_payload.assign(d_def->max_len, 0);
}

void message::set_payload(const std::uint8_t* p, std::size_t n)
{
    std::fill(d_payload.begin(), d_payload.end(), 0);
    std::copy(p, p + std::min(n, d_payload.size()), d_payload.begin());
}

const field_def& message::find(const std::string& field, std::size_t index) const
{
    const field_def* f = d_def->field(field);
    if (!f)
        throw std::invalid_argument("mavlink " + d_def->name + ": no field '" + field +
                                    "'");
    if (index >= f->elements())
        throw std::out_of_range("mavlink " + d_def->name + "." + field + "[" +
                                std::to_string(index) + "]: index beyond its " +
                                std::to_string(f->elements()) + " elements");
    return *f;
}

void message::set(const std::string& field, double v, std::size_t index)
{
    const field_def& f = find(field, index);
    std::uint8_t* p = d_payload.data() + f.offset + index * size_of(f.type);
    if (f.type == ftype::f32) {
        const float x = static_cast<float>(v);
        std::uint32_t u;
        std::memcpy(&u, &x, 4);
        put_le(p, u, 4);
    } else if (f.type == ftype::f64) {
        std::uint64_t u;
        std::memcpy(&u, &v, 8);
        put_le(p, u, 8);
    } else if (is_signed_type(f.type)) {
        const double bits = 8.0 * size_of(f.type) - 1.0;
        const double hi = std::ldexp(1.0, static_cast<int>(bits)) - 1.0;
        const double c = std::isnan(v) ? 0.0 : std::clamp(std::trunc(v), -hi - 1.0, hi);
        // For 64 bits hi rounds up to 2^63, which no int64 holds: saturate exactly.
        set_int(field,
                c >= 9223372036854775808.0 ? std::numeric_limits<std::int64_t>::max()
                                           : static_cast<std::int64_t>(c),
                index);
    } else {
        const double hi = std::ldexp(1.0, static_cast<int>(8 * size_of(f.type))) - 1.0;
        const double c = std::isnan(v) ? 0.0 : std::clamp(std::trunc(v), 0.0, hi);
        set_uint(field,
                 c >= 18446744073709551616.0 ? std::numeric_limits<std::uint64_t>::max()
                                             : static_cast<std::uint64_t>(c),
                 index);
    }
}

double message::get(const std::string& field, std::size_t index) const
{
    const field_def& f = find(field, index);
    const std::uint8_t* p = d_payload.data() + f.offset + index * size_of(f.type);
    if (f.type == ftype::f32) {
        const std::uint32_t u = static_cast<std::uint32_t>(get_le(p, 4));
        float x;
        std::memcpy(&x, &u, 4);
        return x;
    }
    if (f.type == ftype::f64) {
        const std::uint64_t u = get_le(p, 8);
        double x;
        std::memcpy(&x, &u, 8);
        return x;
    }
    return is_signed_type(f.type) ? static_cast<double>(get_int(field, index))
                                  : static_cast<double>(get_uint(field, index));
}

void message::set_int(const std::string& field, std::int64_t v, std::size_t index)
{
    set_uint(field, static_cast<std::uint64_t>(v), index);
}

void message::set_uint(const std::string& field, std::uint64_t v, std::size_t index)
{
    const field_def& f = find(field, index);
    put_le(d_payload.data() + f.offset + index * size_of(f.type), v, size_of(f.type));
}

std::int64_t message::get_int(const std::string& field, std::size_t index) const
{
    const field_def& f = find(field, index);
    const std::size_t n = size_of(f.type);
    const std::uint64_t u = get_le(d_payload.data() + f.offset + index * n, n);
    if (!is_signed_type(f.type) || n == 8)
        return static_cast<std::int64_t>(u);
    const std::uint64_t sign = std::uint64_t{ 1 } << (8 * n - 1);
    return static_cast<std::int64_t>((u ^ sign) - sign); // sign-extend
}

std::uint64_t message::get_uint(const std::string& field, std::size_t index) const
{
    const field_def& f = find(field, index);
    const std::size_t n = size_of(f.type);
    return get_le(d_payload.data() + f.offset + index * n, n);
}

void message::set_text(const std::string& field, const std::string& text)
{
    const field_def& f = find(field, 0);
    std::uint8_t* p = d_payload.data() + f.offset;
    std::fill(p, p + f.bytes(), 0);
    std::memcpy(p, text.data(), std::min(text.size(), f.bytes()));
}

std::string message::get_text(const std::string& field) const
{
    const field_def& f = find(field, 0);
    const char* p = reinterpret_cast<const char*>(d_payload.data() + f.offset);
    return std::string(p, strnlen(p, f.bytes()));
}

// --- framing --------------------------------------------------------------------

std::vector<std::uint8_t>
encode(const message& m, const header& h, const signing* sign, std::uint64_t timestamp)
{
    const auto& pl = m.payload();
    std::size_t len = pl.size();
    while (len > 1 && pl[len - 1] == 0)
        --len; // zero-byte truncation (the first byte always stays)
    std::vector<std::uint8_t> f(V2_HEADER + len + 2 + (sign ? SIGNATURE : 0));
    f[0] = MAGIC_V2;
    f[1] = static_cast<std::uint8_t>(len);
    f[2] = sign ? IFLAG_SIGNED : 0;
    f[3] = 0;
    f[4] = h.seq;
    f[5] = h.sysid;
    f[6] = h.compid;
    put_le(&f[7], m.id(), 3);
    std::copy(pl.begin(), pl.begin() + len, f.begin() + V2_HEADER);
    std::uint16_t crc = crc_x25(&f[1], V2_HEADER - 1 + len);
    crc = crc_x25(&m.def().crc_extra, 1, crc);
    put_le(&f[V2_HEADER + len], crc, 2);
    if (sign) {
        std::uint8_t* s = &f[V2_HEADER + len + 2];
        s[0] = sign->link_id;
        put_le(s + 1, timestamp & 0xFFFFFFFFFFFFull, 6);
        const auto sig = signature_of(sign->key, f.data(), V2_HEADER + len + 2 + 7);
        std::copy(sig.begin(), sig.end(), s + 7);
    }
    return f;
}

std::vector<std::uint8_t> encode_v1(const message& m, const header& h)
{
    if (m.id() > 255)
        throw std::invalid_argument("mavlink " + m.def().name +
                                    ": id above 255 has no MAVLink 1 frame");
    const std::size_t len = m.def().base_len;
    std::vector<std::uint8_t> f(V1_HEADER + len + 2);
    f[0] = MAGIC_V1;
    f[1] = static_cast<std::uint8_t>(len);
    f[2] = h.seq;
    f[3] = h.sysid;
    f[4] = h.compid;
    f[5] = static_cast<std::uint8_t>(m.id());
    std::copy(m.payload().begin(), m.payload().begin() + len, f.begin() + V1_HEADER);
    std::uint16_t crc = crc_x25(&f[1], V1_HEADER - 1 + len);
    crc = crc_x25(&m.def().crc_extra, 1, crc);
    put_le(&f[V1_HEADER + len], crc, 2);
    return f;
}

message frame::decode() const
{
    message m(msgid);
    m.set_payload(payload.data(), payload.size());
    return m;
}

void parser::require_signing(const std::array<std::uint8_t, 32>& key,
                             bool accept_unsigned)
{
    d_signing = true;
    d_key = key;
    d_accept_unsigned = accept_unsigned;
}

void parser::push(const std::uint8_t* data, std::size_t n, std::vector<frame>& out)
{
    d_buf.insert(d_buf.end(), data, data + n);
    while (take_one(out)) {
    }
}

bool parser::check_signature(const frame& f, std::size_t signed_len)
{
    const std::uint8_t* s = d_buf.data() + signed_len - 7;
    if (signature_of(d_key, d_buf.data(), signed_len) !=
        std::array<std::uint8_t, 6>{ s[7], s[8], s[9], s[10], s[11], s[12] }) {
        ++d_stats.bad_signature;
        return false;
    }
    // Replay: each stream's timestamps must increase, and none may lag the newest
    // seen on any stream by more than a minute (the protocol's rule).
    const auto key = std::make_tuple(f.hdr.sysid, f.hdr.compid, f.link_id);
    const auto it = d_last.find(key);
    if ((it != d_last.end() && f.timestamp <= it->second) ||
        f.timestamp + 6000000 < d_newest) {
        ++d_stats.replayed;
        return false;
    }
    d_last[key] = f.timestamp;
    d_newest = std::max(d_newest, f.timestamp);
    return true;
}

// Take one frame (or drop one byte) from the front of the buffer; false when more
// bytes are needed.
bool parser::take_one(std::vector<frame>& out)
{
    std::size_t start = 0;
    while (start < d_buf.size() && d_buf[start] != MAGIC_V1 && d_buf[start] != MAGIC_V2)
        ++start;
    d_stats.skipped_bytes += start;
    d_buf.erase(d_buf.begin(), d_buf.begin() + start);
    if (d_buf.size() < 3)
        return false;
    const bool v2 = d_buf[0] == MAGIC_V2;
    const std::size_t head = v2 ? V2_HEADER : V1_HEADER;
    if (d_buf.size() < head)
        return false;
    auto drop = [this](std::size_t n) {
        d_buf.erase(d_buf.begin(), d_buf.begin() + n);
        return true;
    };
    const std::size_t len = d_buf[1];
    frame f;
    f.version = v2 ? 2 : 1;
    if (v2) {
        f.incompat_flags = d_buf[2];
        f.compat_flags = d_buf[3];
        f.hdr = header{ d_buf[4], d_buf[5], d_buf[6] };
        f.msgid = static_cast<std::uint32_t>(get_le(&d_buf[7], 3));
    } else {
        f.hdr = header{ d_buf[2], d_buf[3], d_buf[4] };
        f.msgid = d_buf[5];
    }
    // Judged on the header alone, so that a false start (a magic byte inside other
    // data) is left at once instead of waiting for the length it claims: flags we do
    // not understand, an id outside the dialect (its CRC cannot be checked), a length
    // beyond the message's with all its extensions, or, in MAVLink 1 (no truncation),
    // short of the message without them (some senders put the extensions in v1
    // frames: accepted). As the reference C library with its length check.
    const frame_info* info = find_frame(f.msgid);
    if ((v2 && (f.incompat_flags & ~IFLAG_SIGNED)) || !info) {
        ++d_stats.unknown;
        return drop(1);
    }
    if (len > info->max_len || (!v2 && len < info->base_len)) {
        ++d_stats.bad_crc;
        return drop(1);
    }
    const bool is_signed = v2 && (f.incompat_flags & IFLAG_SIGNED);
    const std::size_t total = head + len + 2 + (is_signed ? SIGNATURE : 0);
    if (d_buf.size() < total)
        return false;
    std::uint16_t crc = crc_x25(&d_buf[1], head - 1 + len);
    crc = crc_x25(&info->crc_extra, 1, crc);
    if (crc != get_le(&d_buf[head + len], 2)) {
        ++d_stats.bad_crc;
        return drop(1);
    }
    f.payload.assign(d_buf.begin() + head, d_buf.begin() + head + len);
    if (is_signed) {
        f.is_signed = true;
        f.link_id = d_buf[head + len + 2];
        f.timestamp = get_le(&d_buf[head + len + 3], 6);
    }
    if (d_signing) {
        const bool ok = is_signed
                            ? check_signature(f, head + len + 2 + 7)
                            : (d_accept_unsigned || (++d_stats.bad_signature, false));
        if (!ok)
            return drop(total);
    }
    ++d_stats.frames;
    if (!f.known())
        ++d_stats.undecoded;
    f.raw.assign(d_buf.begin(), d_buf.begin() + total);
    out.push_back(std::move(f));
    return drop(total);
}

} // namespace mavlink
} // namespace rfseek
} // namespace gr
