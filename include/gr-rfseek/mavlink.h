/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * mavlink: a MAVLink 2 codec of our own (no GNU Radio dependency), for the autopilot
 * link (docs/live.md "Autopilot"). Framing of v2 frames (and v1 frames parsed as well),
 * CRC-16/MCRF4XX with each message's CRC_EXTRA, zero-byte truncation of payloads,
 * sequence numbers, system and component ids, and optional message signing (SHA-256
 * from OpenSSL; link id, 48-bit timestamps in 10 us units, replay rejection). The
 * message facts (ids, field order, CRC_EXTRA) are data generated from the official
 * definitions (lib/mavlink_tables.inc, scripts/gen_mavlink_tables.py).
 */

#ifndef INCLUDED_RFSEEK_MAVLINK_H
#define INCLUDED_RFSEEK_MAVLINK_H

#include <gr-rfseek/api.h>
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace gr {
namespace rfseek {
namespace mavlink {

//! A field's wire type.
enum class ftype : std::uint8_t { u8, i8, u16, i16, u32, i32, u64, i64, f32, f64, chr };
//! Bytes of one element of type t.
RFSEEK_API std::size_t size_of(ftype t);
//! The MAVLink type name ("uint8_t", "float", "char", ...).
RFSEEK_API const char* type_name(ftype t);

//! One field of a message definition.
struct RFSEEK_API field_def {
    std::string name;
    ftype type;
    std::size_t count;  //!< array length; 0 = scalar
    bool extension;     //!< a MAVLink 2 extension field
    std::size_t offset; //!< byte offset in the payload (wire order)
    std::size_t elements() const { return count ? count : 1; }
    std::size_t bytes() const { return size_of(type) * elements(); }
};

//! A message definition (fields in wire order).
struct RFSEEK_API message_def {
    std::uint32_t id = 0;
    std::string name;
    std::uint8_t crc_extra = 0;
    std::vector<field_def> fields;
    std::size_t base_len = 0; //!< payload bytes without extensions (a v1 frame's length)
    std::size_t max_len = 0;  //!< payload bytes with the extensions
    //! The field named `name`, or nullptr.
    const field_def* field(const std::string& name) const;
};

//! What the parser needs to check and skip a frame of any message of the dialect
//! (ArduPilot's, which includes the common set), decoded or not.
struct RFSEEK_API frame_info {
    std::uint32_t id;
    std::uint8_t crc_extra;
    std::uint8_t base_len; //!< payload bytes without extensions
    std::uint8_t max_len;  //!< payload bytes with the extensions
};
//! The frame facts of id, or nullptr for an id outside the dialect.
RFSEEK_API const frame_info* find_frame(std::uint32_t id);

//! Every message the codec decodes, by id.
RFSEEK_API const std::map<std::uint32_t, message_def>& definitions();
//! The definition of id / name, or nullptr.
RFSEEK_API const message_def* find_message(std::uint32_t id);
RFSEEK_API const message_def* find_message(const std::string& name);

//! CRC-16/MCRF4XX (the X.25 CRC MAVLink uses), continuing from crc.
RFSEEK_API std::uint16_t
crc_x25(const std::uint8_t* data, std::size_t n, std::uint16_t crc = 0xFFFF);
//! CRC_EXTRA of a definition, computed from its name and fields as the protocol says.
RFSEEK_API std::uint8_t compute_crc_extra(const message_def& d);

//! A message: its definition and its full (untruncated) payload, little endian.
class RFSEEK_API message
{
public:
    //! Throws std::invalid_argument for an unknown name / id.
    explicit message(const std::string& name);
    explicit message(std::uint32_t id);
    const message_def& def() const { return *d_def; }
    std::uint32_t id() const { return d_def->id; }
    const std::vector<std::uint8_t>& payload() const { return d_payload; }
    //! Set from wire bytes (shorter: zero-extended; longer: cut to the definition).
    void set_payload(const std::uint8_t* p, std::size_t n);

    //! Numeric fields (element `index` of an array). Values are converted to the
    //! field's type: integers rounded toward zero and clamped to its range.
    //! Throws std::invalid_argument naming an unknown field, std::out_of_range for
    //! an index beyond the array.
    void set(const std::string& field, double value, std::size_t index = 0);
    double get(const std::string& field, std::size_t index = 0) const;
    //! 64-bit integers exactly (any integer field).
    void set_int(const std::string& field, std::int64_t value, std::size_t index = 0);
    void set_uint(const std::string& field, std::uint64_t value, std::size_t index = 0);
    std::int64_t get_int(const std::string& field, std::size_t index = 0) const;
    std::uint64_t get_uint(const std::string& field, std::size_t index = 0) const;
    //! char[] fields: up to the array length, NUL-padded.
    void set_text(const std::string& field, const std::string& text);
    std::string get_text(const std::string& field) const;

    bool operator==(const message& o) const
    {
        return d_def == o.d_def && d_payload == o.d_payload;
    }

private:
    const field_def& find(const std::string& field, std::size_t index) const;
    const message_def* d_def;
    std::vector<std::uint8_t> d_payload;
};

//! The sender's identity and sequence number of one frame.
struct RFSEEK_API header {
    std::uint8_t seq = 0;
    std::uint8_t sysid = 1;
    std::uint8_t compid = 1;
};

//! A signing secret and the link it signs (MAVLink 2 message signing).
struct RFSEEK_API signing {
    std::array<std::uint8_t, 32> key{};
    std::uint8_t link_id = 0;
};

//! A MAVLink 2 frame: payload truncated of trailing zeros (at least one byte), signed
//! with `sign` at `timestamp` (10 us units since 2015-01-01) when given.
RFSEEK_API std::vector<std::uint8_t> encode(const message& m,
                                            const header& h,
                                            const signing* sign = nullptr,
                                            std::uint64_t timestamp = 0);
//! A MAVLink 1 frame (ids < 256, no extensions, no truncation).
RFSEEK_API std::vector<std::uint8_t> encode_v1(const message& m, const header& h);

//! One frame as received.
struct RFSEEK_API frame {
    int version = 2;
    std::uint8_t incompat_flags = 0, compat_flags = 0;
    header hdr;
    std::uint32_t msgid = 0;
    std::vector<std::uint8_t> payload; //!< as on the wire (possibly truncated)
    bool is_signed = false;
    std::uint8_t link_id = 0;
    std::uint64_t timestamp = 0;
    std::vector<std::uint8_t> raw; //!< the whole frame as received (for logs)
    //! Whether the codec has the message's definition (decode() works).
    bool known() const { return find_message(msgid) != nullptr; }
    //! The message, payload zero-extended to its definition (throws
    //! std::invalid_argument when !known()).
    message decode() const;
};

//! Byte-stream parser: finds frames, checks their CRC (with the CRC_EXTRA of the
//! dialect's messages), and, when a key is set, their signature and timestamp. Every
//! valid frame is returned, decodable or not (frame::known()).
class RFSEEK_API parser
{
public:
    struct counters {
        std::uint64_t frames = 0;        //!< accepted
        std::uint64_t undecoded = 0;     //!< accepted, without a definition to decode
        std::uint64_t bad_crc = 0;       //!< CRC or length mismatch (resynchronised)
        std::uint64_t unknown = 0;       //!< id outside the dialect, or unknown flags
        std::uint64_t bad_signature = 0; //!< signature wrong, or unsigned when required
        std::uint64_t replayed = 0;      //!< timestamp not newer than its stream's last
        std::uint64_t skipped_bytes = 0; //!< bytes outside any frame
    };
    //! Check signatures with `key`: signed frames must verify and be newer than the
    //! last one of their stream (system, component, link); unsigned ones are refused
    //! unless accept_unsigned.
    void require_signing(const std::array<std::uint8_t, 32>& key,
                         bool accept_unsigned = false);
    //! Feed bytes; complete, valid frames are appended to `out`.
    void push(const std::uint8_t* data, std::size_t n, std::vector<frame>& out);
    const counters& stats() const { return d_stats; }
    //! The newest signing timestamp accepted (0: none yet).
    std::uint64_t newest_timestamp() const { return d_newest; }

private:
    bool take_one(std::vector<frame>& out);
    bool check_signature(const frame& f, std::size_t signed_len);
    std::vector<std::uint8_t> d_buf;
    counters d_stats;
    bool d_signing = false, d_accept_unsigned = false;
    std::array<std::uint8_t, 32> d_key{};
    std::map<std::tuple<std::uint8_t, std::uint8_t, std::uint8_t>, std::uint64_t> d_last;
    std::uint64_t d_newest = 0; //!< the newest timestamp accepted on any stream
};

} // namespace mavlink
} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_MAVLINK_H */
