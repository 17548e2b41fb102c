#pragma once
// HDF5 helpers shared by the field output (fields_out.cpp) and checkpoints
// (checkpoint.cpp). Internal to src/io: includes hdf5.h.
#include <hdf5.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/host_access.hpp"
#include "kernels/box_copy.hpp"

namespace voigt::h5 {

// Owns one hid_t and closes it with the matching H5?close on scope exit.
class Id {
 public:
  using Closer = herr_t (*)(hid_t);
  Id(hid_t id, Closer close, const char* what, const std::string& path) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error(path + ": HDF5 " + what + " failed");
  }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  ~Id() { if (id_ >= 0) close_(id_); }
  operator hid_t() const { return id_; }
  // Explicit close so a failing final flush (H5Fclose) is reported.
  void close(const std::string& path) {
    hid_t id = id_;
    id_ = -1;
    if (close_(id) < 0) throw std::runtime_error(path + ": HDF5 close failed");
  }
  hid_t get() const { return id_; }

 private:
  hid_t id_;
  Closer close_;
};

inline void check(herr_t e, const char* what, const std::string& path) {
  if (e < 0) throw std::runtime_error(path + ": HDF5 " + what + " failed");
}
inline void check(herr_t e, const std::string& what, const std::string& path) { check(e, what.c_str(), path); }

// Why a write into `dir` may have failed, for error messages ("" if no idea):
// HDF5's own errors do not say, and errno is not reliable after them.
inline std::string diagnoseWrite(const std::string& dir) {
  struct statvfs sv;
  if (::statvfs(dir.c_str(), &sv) == 0) {
    if (sv.f_flag & ST_RDONLY) return "the file system of " + dir + " is read-only";
    const double freeBytes = double(sv.f_bavail) * double(sv.f_frsize);
    if (freeBytes < 1048576.0)
      return "disk full: No space left on device (" + std::to_string((long long)freeBytes) + " bytes free in " + dir +
             ")";
  }
  if (::access(dir.c_str(), W_OK) != 0) return dir + " is not writable: " + std::strerror(errno);
  return "";
}

// Collective: refuses (throws, on every rank) to start writing `bytes` into
// `dir` when its file system has less free space than that plus a margin.
// HDF5 cannot recover from a write that fails half-way (its clean-up of the
// half-closed file crashes at MPI_Finalize), so a full disk is caught here.
inline void requireSpace(const Grid& g, const std::string& dir, double bytes, const std::string& what) {
  double freeBytes = -1;
  if (g.rank == 0) {
    struct statvfs sv;
    if (::statvfs(dir.c_str(), &sv) == 0) freeBytes = double(sv.f_bavail) * double(sv.f_frsize);
  }
  MPI_Bcast(&freeBytes, 1, MPI_DOUBLE, 0, g.comm);
  const double need = bytes * 1.02 + 65536;
  if (freeBytes >= 0 && freeBytes < need)
    throw std::runtime_error(what + ": disk full: No space left on device (" + dir + " has " +
                             std::to_string((long long)freeBytes) + " bytes free, the file needs about " +
                             std::to_string((long long)need) + ")");
}

template <class T> hid_t memType();
template <> inline hid_t memType<double>() { return H5T_NATIVE_DOUBLE; }
template <> inline hid_t memType<int>() { return H5T_NATIVE_INT; }
template <class T> hid_t fileType();
template <> inline hid_t fileType<double>() { return H5T_IEEE_F64LE; }
template <> inline hid_t fileType<int>() { return H5T_STD_I32LE; }

// A global box of points [b, e) (global indices, x y z) of a dataset of
// global size gn (x y z). Stored in C order (z, y, x[, comp]).
struct Box {
  int b[3], e[3], gn[3];
  bool empty() const { return e[0] <= b[0] || e[1] <= b[1] || e[2] <= b[2]; }
};

// Collective: creates dataset `name` in `file` and writes the box of every
// component (1: rank-3 dataset; 3 or more: rank-4 with components last).
// View is a 3-D LayoutLeft view over the grid's local index space.
template <class View>
void writeBox(hid_t file, hid_t dxpl, const Grid& g, const std::string& name, const std::vector<View>& comps,
              const Box& box, const std::string& path) {
  using T = typename View::non_const_value_type;
  using Packed = Kokkos::View<T****, Kokkos::LayoutRight, MemSpace>;
  const int nc = int(comps.size());
  const bool empty = box.empty();
  hsize_t gdims[4] = {hsize_t(box.gn[2]), hsize_t(box.gn[1]), hsize_t(box.gn[0]), hsize_t(nc)};
  hsize_t start[4] = {hsize_t(box.b[2]), hsize_t(box.b[1]), hsize_t(box.b[0]), 0};
  hsize_t count[4] = {empty ? 0 : hsize_t(box.e[2] - box.b[2]), empty ? 0 : hsize_t(box.e[1] - box.b[1]),
                      empty ? 0 : hsize_t(box.e[0] - box.b[0]), hsize_t(nc)};
  const int rank = nc == 1 ? 3 : 4;

  // Pack owned points on the execution space, then one copy to the host.
  Packed buf("io::packed", count[0], count[1], count[2], nc);
  const int lb[3] = {g.local(0, box.b[0]), g.local(1, box.b[1]), g.local(2, box.b[2])};
  const int le[3] = {g.local(0, box.e[0]), g.local(1, box.e[1]), g.local(2, box.e[2])};
  for (int c = 0; c < nc && !empty; ++c) copyBoxPacked<true>(comps[c], lb, le, buf, c);
  auto host = toHost(buf, "hdf5_write");

  Id fspace(H5Screate_simple(rank, gdims, nullptr), H5Sclose, "H5Screate_simple", path);
  Id dset(H5Dcreate2(file, name.c_str(), fileType<T>(), fspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
          ("dataset create '" + name + "'").c_str(), path);
  hsize_t mdims[4] = {std::max<hsize_t>(count[0], 1), std::max<hsize_t>(count[1], 1),
                      std::max<hsize_t>(count[2], 1), hsize_t(nc)};
  Id mspace(H5Screate_simple(rank, mdims, nullptr), H5Sclose, "H5Screate_simple", path);
  if (empty) { // still take part in the collective write
    check(H5Sselect_none(fspace), "H5Sselect_none", path);
    check(H5Sselect_none(mspace), "H5Sselect_none", path);
  } else {
    check(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr), "H5Sselect_hyperslab",
          path);
  }
  check(H5Dwrite(dset, memType<T>(), mspace, fspace, dxpl, host.data()), "write of '" + name + "'", path);
}

// Collective: reads the box of dataset `name` into the local points of comps.
// The dataset must have exactly the global size box.gn and comps.size() components.
template <class View>
void readBox(hid_t file, hid_t dxpl, const Grid& g, const std::string& name, const std::vector<View>& comps,
             const Box& box, const std::string& path) {
  using T = typename View::non_const_value_type;
  using Packed = Kokkos::View<T****, Kokkos::LayoutRight, MemSpace>;
  const int nc = int(comps.size());
  const bool empty = box.empty();
  const int rank = nc == 1 ? 3 : 4;
  Id dset(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose, ("dataset open '" + name + "'").c_str(), path);
  Id fspace(H5Dget_space(dset), H5Sclose, "H5Dget_space", path);
  hsize_t dims[4] = {0, 0, 0, 1};
  const int frank = H5Sget_simple_extent_ndims(fspace);
  if (frank != rank) throw std::runtime_error(path + ": dataset '" + name + "' has the wrong number of components");
  H5Sget_simple_extent_dims(fspace, dims, nullptr);
  if (dims[0] != hsize_t(box.gn[2]) || dims[1] != hsize_t(box.gn[1]) || dims[2] != hsize_t(box.gn[0]) ||
      (rank == 4 && dims[3] != hsize_t(nc)))
    throw std::runtime_error(path + ": dataset '" + name + "' is " + std::to_string(dims[2]) + " x " +
                             std::to_string(dims[1]) + " x " + std::to_string(dims[0]) + ", the grid needs " +
                             std::to_string(box.gn[0]) + " x " + std::to_string(box.gn[1]) + " x " +
                             std::to_string(box.gn[2]));
  hsize_t start[4] = {hsize_t(box.b[2]), hsize_t(box.b[1]), hsize_t(box.b[0]), 0};
  hsize_t count[4] = {empty ? 0 : hsize_t(box.e[2] - box.b[2]), empty ? 0 : hsize_t(box.e[1] - box.b[1]),
                      empty ? 0 : hsize_t(box.e[0] - box.b[0]), hsize_t(nc)};
  Packed buf("io::unpacked", count[0], count[1], count[2], nc);
  auto host = Kokkos::create_mirror_view(buf);
  hsize_t mdims[4] = {std::max<hsize_t>(count[0], 1), std::max<hsize_t>(count[1], 1),
                      std::max<hsize_t>(count[2], 1), hsize_t(nc)};
  Id mspace(H5Screate_simple(rank, mdims, nullptr), H5Sclose, "H5Screate_simple", path);
  if (empty) {
    check(H5Sselect_none(fspace), "H5Sselect_none", path);
    check(H5Sselect_none(mspace), "H5Sselect_none", path);
  } else {
    check(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr), "H5Sselect_hyperslab",
          path);
  }
  check(H5Dread(dset, memType<T>(), mspace, fspace, dxpl, host.data()), "read of '" + name + "'", path);
  if (empty) return;
  toDevice(buf, host, "hdf5_read");
  const int lb[3] = {g.local(0, box.b[0]), g.local(1, box.b[1]), g.local(2, box.b[2])};
  const int le[3] = {g.local(0, box.e[0]), g.local(1, box.e[1]), g.local(2, box.e[2])};
  for (int c = 0; c < nc; ++c) copyBoxPacked<false>(comps[c], lb, le, buf, c);
  Kokkos::fence();
}

} // namespace voigt::h5
