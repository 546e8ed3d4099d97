#pragma once
// Reading a netCDF-4 file in a child process. netCDF-4 files are HDF5 files,
// and HDF5 1.10 (Debian 12) is not robust to corrupt ones: fuzzing found
// inputs on which it reads out of bounds and dies with SIGSEGV, and others on
// which it loops forever, both while netCDF-C reads a variable's dimension
// scales (docs/reliability.md, "Known upstream defects"). Neither can be
// fixed or caught in this process. A forked child does the read instead and
// hands the series back through a pipe, so that the crash or the hang becomes
// an InputError naming the file, and the tool exits 1 with that message.
// Classic files are read in-process: obscura walks their header first
// (netcdf_classic_check.h) and netCDF-C parses them itself. Internal to io/.
#include <filesystem>
#include <functional>
#include <string>

#include "obscura/medium/concentration_series.h"

namespace obscura::netcdf_cf {

// True when netCDF-C would open the file as netCDF-4: HDF5's signature at
// byte 0, or, when the file does not start with a classic magic number
// ("CDF"), at byte 512, 1024, 2048, ... (netCDF-C's check_file_type follows
// HDF5's superblock search).
bool is_hdf5_container(const std::filesystem::path& path);

// How long the child may take to read everything before the data (the file's
// structure, the axes, the coordinates and the attributes): far more than any
// sane file needs, so that only a loop inside HDF5 reaches it. The data
// themselves have no limit, since a large file may take minutes.
inline constexpr double kHeaderTimeLimitS = 60.0;

// The read the child runs: it calls `header_read` once everything before the
// data is read (which ends the time limit) and returns the series.
using ChildRead = std::function<ConcentrationSeries(const std::function<void()>& header_read)>;

// Runs `read` in a forked child and returns its series. An obscura::Error the
// child throws is thrown again here with the same message (an InputError
// with the same file, field and detail; an InternalError as one). Throws
// InputError naming `file` when the child dies (a signal or an exit status)
// or has not called `header_read` within `header_limit_s` (the child is then
// killed); Error when no child can be started. The caller holds
// netcdf_mutex(), so that no other thread is inside netCDF-C at the fork.
ConcentrationSeries read_in_child_process(const std::string& file, const ChildRead& read,
                                          double header_limit_s = kHeaderTimeLimitS);

}  // namespace obscura::netcdf_cf
