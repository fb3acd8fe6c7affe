/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(mavlink.h) */
/* BINDTOOL_HEADER_FILE_HASH(88a796875ca73ed3710fa6ed3f7e0830) */

#include <gr-rfseek/mavlink.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace {

using namespace gr::rfseek::mavlink;

py::bytes to_bytes(const std::vector<std::uint8_t>& v)
{
    return py::bytes(reinterpret_cast<const char*>(v.data()), v.size());
}

std::vector<std::uint8_t> from_bytes(const py::bytes& b)
{
    const std::string s = b;
    return std::vector<std::uint8_t>(s.begin(), s.end());
}

// A message's fields as a dict: numbers (arrays as lists), char[] as str.
py::dict fields_of(const message& m)
{
    py::dict d;
    for (const field_def& f : m.def().fields) {
        if (f.type == ftype::chr) {
            d[f.name.c_str()] = m.get_text(f.name);
        } else if (f.count) {
            py::list l;
            for (std::size_t i = 0; i < f.count; ++i)
                l.append(
                    f.type == ftype::u64   ? py::object(py::int_(m.get_uint(f.name, i)))
                    : f.type == ftype::i64 ? py::object(py::int_(m.get_int(f.name, i)))
                                           : py::object(py::float_(m.get(f.name, i))));
            d[f.name.c_str()] = l;
        } else if (f.type == ftype::f32 || f.type == ftype::f64) {
            d[f.name.c_str()] = m.get(f.name);
        } else if (f.type == ftype::i8 || f.type == ftype::i16 || f.type == ftype::i32 ||
                   f.type == ftype::i64) {
            d[f.name.c_str()] = m.get_int(f.name);
        } else {
            d[f.name.c_str()] = m.get_uint(f.name);
        }
    }
    return d;
}

void bind_messages(py::module& m)
{
    m.def(
        "crc_x25",
        [](const py::bytes& data, std::uint16_t crc) {
            const auto v = from_bytes(data);
            return crc_x25(v.data(), v.size(), crc);
        },
        py::arg("data"),
        py::arg("crc") = 0xFFFF,
        "CRC-16/MCRF4XX of data, continuing from crc.");
    m.def(
        "message_names",
        []() {
            std::vector<std::string> names;
            for (const auto& kv : definitions())
                names.push_back(kv.second.name);
            return names;
        },
        "Names of the messages the codec decodes.");

    py::class_<message>(m, "message", "A MAVLink message: a definition and its payload.")
        .def(py::init<const std::string&>(), py::arg("name"), "An all-zero message.")
        .def(py::init<std::uint32_t>(), py::arg("id"))
        .def_property_readonly(
            "name", [](const message& x) { return x.def().name; }, "Message name.")
        .def_property_readonly("id", &message::id, "Message id.")
        .def_property_readonly(
            "payload",
            [](const message& x) { return to_bytes(x.payload()); },
            "The full payload, little endian, wire order.")
        .def("set",
             &message::set,
             py::arg("field"),
             py::arg("value"),
             py::arg("index") = 0,
             "Set a numeric field (converted to its type: rounded toward zero, clamped).")
        .def("get",
             &message::get,
             py::arg("field"),
             py::arg("index") = 0,
             "A numeric field as a float.")
        .def("set_int",
             &message::set_int,
             py::arg("field"),
             py::arg("value"),
             py::arg("index") = 0)
        .def("get_int", &message::get_int, py::arg("field"), py::arg("index") = 0)
        .def("set_text", &message::set_text, py::arg("field"), py::arg("text"))
        .def("get_text", &message::get_text, py::arg("field"))
        .def("fields", &fields_of, "Every field, as a dict.")
        .def("__eq__", &message::operator==)
        .def("__repr__", [](const message& x) {
            return "<mavlink " + x.def().name + " " +
                   py::str(fields_of(x)).cast<std::string>() + ">";
        });
}

void bind_frames(py::module& m)
{
    py::class_<header>(m, "header", "Sequence number, system and component ids.")
        .def(py::init([](int seq, int sysid, int compid) {
                 return header{ static_cast<std::uint8_t>(seq),
                                static_cast<std::uint8_t>(sysid),
                                static_cast<std::uint8_t>(compid) };
             }),
             py::arg("seq") = 0,
             py::arg("sysid") = 1,
             py::arg("compid") = 1)
        .def_readwrite("seq", &header::seq)
        .def_readwrite("sysid", &header::sysid)
        .def_readwrite("compid", &header::compid);

    m.def(
        "encode",
        [](const message& msg,
           const header& h,
           const py::object& key,
           int link_id,
           std::uint64_t timestamp) {
            if (key.is_none())
                return to_bytes(encode(msg, h));
            const auto k = from_bytes(key.cast<py::bytes>());
            if (k.size() != 32)
                throw py::value_error("mavlink.encode: key must be 32 bytes");
            signing s;
            std::copy(k.begin(), k.end(), s.key.begin());
            s.link_id = static_cast<std::uint8_t>(link_id);
            return to_bytes(encode(msg, h, &s, timestamp));
        },
        py::arg("msg"),
        py::arg("header") = header{},
        py::arg("key") = py::none(),
        py::arg("link_id") = 0,
        py::arg("timestamp") = 0,
        "A MAVLink 2 frame (signed with the 32-byte key at timestamp, 10 us units since "
        "2015-01-01, when given).");
    m.def(
        "encode_v1",
        [](const message& msg, const header& h) { return to_bytes(encode_v1(msg, h)); },
        py::arg("msg"),
        py::arg("header") = header{},
        "A MAVLink 1 frame.");

    py::class_<frame>(m, "frame", "A frame as received.")
        .def_readonly("version", &frame::version)
        .def_readonly("msgid", &frame::msgid)
        .def_property_readonly("seq", [](const frame& f) { return f.hdr.seq; })
        .def_property_readonly("sysid", [](const frame& f) { return f.hdr.sysid; })
        .def_property_readonly("compid", [](const frame& f) { return f.hdr.compid; })
        .def_readonly("is_signed", &frame::is_signed)
        .def_readonly("link_id", &frame::link_id)
        .def_readonly("timestamp", &frame::timestamp)
        .def_property_readonly(
            "raw", [](const frame& f) { return to_bytes(f.raw); }, "The frame's bytes.")
        .def("known", &frame::known, "Whether the codec decodes this message.")
        .def("decode", &frame::decode, "The message (ValueError when not known()).");

    py::class_<parser>(
        m, "parser", "Byte-stream parser (checks CRC, and signatures if keyed).")
        .def(py::init<>())
        .def(
            "require_signing",
            [](parser& p, const py::bytes& key, bool accept_unsigned) {
                const auto k = from_bytes(key);
                if (k.size() != 32)
                    throw py::value_error("mavlink.parser: key must be 32 bytes");
                std::array<std::uint8_t, 32> a;
                std::copy(k.begin(), k.end(), a.begin());
                p.require_signing(a, accept_unsigned);
            },
            py::arg("key"),
            py::arg("accept_unsigned") = false)
        .def(
            "push",
            [](parser& p, const py::bytes& data) {
                const auto v = from_bytes(data);
                std::vector<frame> out;
                p.push(v.data(), v.size(), out);
                return out;
            },
            py::arg("data"),
            "Feed bytes; returns the complete, valid frames.")
        .def(
            "stats",
            [](const parser& p) {
                const auto& s = p.stats();
                py::dict d;
                d["frames"] = s.frames;
                d["undecoded"] = s.undecoded;
                d["bad_crc"] = s.bad_crc;
                d["unknown"] = s.unknown;
                d["bad_signature"] = s.bad_signature;
                d["replayed"] = s.replayed;
                d["skipped_bytes"] = s.skipped_bytes;
                return d;
            },
            "Counters of accepted and refused frames.");
}

} // namespace

void bind_mavlink(py::module& root)
{
    py::module m = root.def_submodule(
        "mavlink",
        "The module's MAVLink 2 codec (docs/design.md): messages, frames, signing and a "
        "resynchronising parser.");
    bind_messages(m);
    bind_frames(m);
}
