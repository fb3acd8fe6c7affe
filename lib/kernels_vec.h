/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * kernels_vec: the GCC vector types of the kernels (8 and 16 lanes). Internal.
 */

#ifndef INCLUDED_RFSEEK_KERNELS_VEC_H
#define INCLUDED_RFSEEK_KERNELS_VEC_H

namespace gr {
namespace rfseek {
namespace detail {

typedef float v8f __attribute__((vector_size(32)));
typedef int v8i __attribute__((vector_size(32)));
typedef unsigned int v8u __attribute__((vector_size(32)));
typedef float v16f __attribute__((vector_size(64)));
typedef int v16i __attribute__((vector_size(64)));
typedef unsigned int v16u __attribute__((vector_size(64)));

} // namespace detail
} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_KERNELS_VEC_H */
