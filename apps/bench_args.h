/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The benchmark programs' one optional argument, a count: --help prints the usage and
 * exits 0; anything but an integer in [1, max] is a one-line error and exit status 2.
 */

#ifndef INCLUDED_RFSEEK_APPS_BENCH_ARGS_H
#define INCLUDED_RFSEEK_APPS_BENCH_ARGS_H

#include <cstdio>
#include <cstdlib>
#include <string>

inline int bench_count(int argc,
                       char** argv,
                       const char* what,
                       int default_count,
                       int max_count,
                       const char* description)
{
    const char* prog = argc > 0 ? argv[0] : "rfseek-bench";
    if (argc > 2) {
        std::fprintf(stderr,
                     "%s: error: one argument at most (usage: %s [%s])\n",
                     prog,
                     prog,
                     what);
        std::exit(2);
    }
    if (argc < 2)
        return default_count;
    const std::string arg = argv[1];
    if (arg == "-h" || arg == "--help") {
        std::printf("usage: %s [%s]\n\n%s\n\n%s: an integer in [1, %d] (default %d)\n",
                    prog,
                    what,
                    description,
                    what,
                    max_count,
                    default_count);
        std::exit(0);
    }
    char* end = nullptr;
    const long v = std::strtol(arg.c_str(), &end, 10);
    if (arg.empty() || *end != '\0' || v < 1 || v > max_count) {
        std::fprintf(
            stderr,
            "%s: error: %s = '%s': must be an integer in [1, %d] (usage: %s [%s])\n",
            prog,
            what,
            arg.c_str(),
            max_count,
            prog,
            what);
        std::exit(2);
    }
    return static_cast<int>(v);
}

#endif /* INCLUDED_RFSEEK_APPS_BENCH_ARGS_H */
