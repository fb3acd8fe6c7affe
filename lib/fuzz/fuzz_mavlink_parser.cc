/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * libFuzzer harness: the MAVLink parser (include/gr-rfseek/mavlink.h) on arbitrary byte
 * streams in arbitrary chunks, with and without a signing key. Every frame it returns
 * must be whole (its raw bytes the length its header says), counted, and, when the codec
 * knows the message, decode and re-encode to a frame the parser reads back to the same
 * payload.
 */

#include <fuzzer/FuzzedDataProvider.h>
#include <gr-rfseek/mavlink.h>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace gr::rfseek::mavlink;

namespace {

[[noreturn]] void fail(const char* what)
{
    std::fprintf(stderr, "%s\n", what);
    std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    FuzzedDataProvider fdp(data, size);
    parser p;
    const int mode = fdp.ConsumeIntegralInRange<int>(0, 2);
    std::array<std::uint8_t, 32> key{};
    key.fill(0x5A);
    if (mode > 0)
        p.require_signing(key, mode == 2);
    std::vector<frame> out;
    while (fdp.remaining_bytes() > 0) {
        const std::size_t n = fdp.ConsumeIntegralInRange<std::size_t>(0, 300);
        const std::vector<std::uint8_t> chunk = fdp.ConsumeBytes<std::uint8_t>(n);
        p.push(chunk.data(), chunk.size(), out);
    }
    if (p.stats().frames != out.size())
        fail("frames counted differ from frames returned");
    for (const frame& f : out) {
        const std::size_t head = f.version == 2 ? 10 : 6;
        const std::size_t total = head + f.payload.size() + 2 + (f.is_signed ? 13 : 0);
        if (f.raw.size() != total || f.raw[1] != f.payload.size())
            fail("a frame's raw bytes are not the length its header says");
        if (mode == 1 && !f.is_signed)
            fail("an unsigned frame passed a parser that requires signing");
        if (!f.known())
            continue;
        const message m = f.decode();
        const std::vector<std::uint8_t> again = encode(m, f.hdr);
        parser q;
        std::vector<frame> back;
        q.push(again.data(), again.size(), back);
        if (back.size() != 1 || !(back[0].decode() == m))
            fail("a decoded frame does not re-encode to itself");
    }
    return 0;
}
