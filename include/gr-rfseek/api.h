/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * Symbol visibility for libgnuradio-rfseek.
 */

#ifndef INCLUDED_RFSEEK_API_H
#define INCLUDED_RFSEEK_API_H

#if defined(_WIN32)
#ifdef gnuradio_rfseek_EXPORTS
#define RFSEEK_API __declspec(dllexport)
#else
#define RFSEEK_API __declspec(dllimport)
#endif
#else
#define RFSEEK_API __attribute__((visibility("default")))
#endif

#endif /* INCLUDED_RFSEEK_API_H */
