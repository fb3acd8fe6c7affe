/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rfseek-montecarlo, the backends that run the rows: threads here, or a Dask cluster
 * through python/rfseek/dask_backend.py (each worker runs study_point::run through the
 * bindings). Rows do not depend on the backend.
 */
#ifndef INCLUDED_RFSEEK_MONTECARLO_BACKENDS_H
#define INCLUDED_RFSEEK_MONTECARLO_BACKENDS_H

#include "options.h"
#include "rows.h"
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace rfseek_mc {

//! Called once per finished row, one call at a time.
using row_callback = std::function<void(const row&)>;

//! Runs every row not done on `threads` threads; a run that raises becomes an error row.
void run_threads(std::vector<row>& rows,
                 const std::vector<gr::rfseek::study_point>& points,
                 unsigned threads,
                 const row_callback& finished);

class dask_backend
{
public:
    //! Writes the jobs (rows to run) to a temporary file and starts the backend.
    dask_backend(const options& o,
                 const std::vector<std::size_t>& jobs,
                 const study_index& ix);
    ~dask_backend();
    dask_backend(const dask_backend&) = delete;
    dask_backend& operator=(const dask_backend&) = delete;

    //! Waits for the cluster; returns its worker count, or 0 after printing why not.
    unsigned start();
    //! Reads the rows as the workers finish them; returns the backend's exit status.
    int run(std::vector<row>& rows, const row_callback& finished);

private:
    bool next(std::string& line);
    int finish();

    std::string d_python;
    std::string d_jobs_file;
    FILE* d_pipe = nullptr;
};

//! Microseconds of one FFTW execute of n points: the floor of a slot's cost.
double fftw_floor_us(int n);

} // namespace rfseek_mc

#endif /* INCLUDED_RFSEEK_MONTECARLO_BACKENDS_H */
