#include "io/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/h5_util.hpp"

namespace voigt {
namespace fs = std::filesystem;
namespace {

constexpr const char* kFormat = "voigt-checkpoint-1";

// Owned points of a field as a global box: cells [c0, c1); nodes [c0, nodeHi)
// of a global array of g.nodes(d) points (periodic node n is node 0).
h5::Box ownedBox(const Grid& g, Centring c) {
  h5::Box b;
  for (int d = 0; d < 3; ++d) {
    b.b[d] = g.c0[d];
    b.e[d] = c == Centring::Node ? g.nodeHi(d) : g.c1[d];
    b.gn[d] = c == Centring::Node ? g.nodes(d) : g.n[d];
  }
  return b;
}

// fn(arrays): field n's arrays as one vector, for writeBox/readBox: its IntField,
// its Field, or its three components.
template <class Fn> void withArrays(const FieldStore& fields, const std::string& n, Fn&& fn) {
  const auto& d = fields.decls().at(n);
  if (d.isInt) return fn(std::vector<IntField>{fields.integer(n)});
  if (d.components == 1) return fn(std::vector<Field>{fields.scalar(n)});
  const VecField v = fields.vector(n);
  fn(std::vector<Field>{v.c[0], v.c[1], v.c[2]});
}

void fsyncPath(const std::string& path, bool dir) {
  const int fd = ::open(path.c_str(), dir ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// Writes `text` as a 1-D char dataset (rank 0's data; collective creation).
void writeText(hid_t file, hid_t dxpl, const Grid& g, const char* name, const std::string& text,
               const std::string& path) {
  unsigned long long n = text.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, g.comm);
  hsize_t dims[1] = {hsize_t(std::max<unsigned long long>(n, 1))};
  h5::Id sp(H5Screate_simple(1, dims, nullptr), H5Sclose, "H5Screate_simple", path);
  h5::Id ds(H5Dcreate2(file, name, H5T_NATIVE_CHAR, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
            "dataset create", path);
  h5::Id ms(H5Screate_simple(1, dims, nullptr), H5Sclose, "H5Screate_simple", path);
  std::string buf = text;
  buf.resize(dims[0], ' ');
  if (g.rank != 0) {
    h5::check(H5Sselect_none(sp), "H5Sselect_none", path);
    h5::check(H5Sselect_none(ms), "H5Sselect_none", path);
  }
  h5::check(H5Dwrite(ds, H5T_NATIVE_CHAR, ms, sp, dxpl, buf.data()), std::string("write of '") + name + "'", path);
}

template <class T>
void writeAttr(hid_t obj, const char* name, hid_t type, const T& v, const std::string& path) {
  h5::Id sp(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate", path);
  h5::Id at(H5Acreate2(obj, name, type, sp, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, "attribute create", path);
  h5::check(H5Awrite(at, type, &v), "attribute write", path);
}

void writeStringAttr(hid_t obj, const char* name, const std::string& v, const std::string& path) {
  h5::Id type(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy", path);
  h5::check(H5Tset_size(type, std::max<size_t>(v.size(), 1)), "H5Tset_size", path);
  h5::Id sp(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate", path);
  h5::Id at(H5Acreate2(obj, name, type, sp, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, "attribute create", path);
  std::string buf = v.empty() ? std::string(1, '\0') : v;
  h5::check(H5Awrite(at, type, buf.data()), "attribute write", path);
}

// Reads the JSON document of an open checkpoint (every rank reads it).
nlohmann::json readMeta(hid_t file, const std::string& path) {
  h5::Id ds(H5Dopen2(file, "meta", H5P_DEFAULT), H5Dclose, "dataset open 'meta' (not a Voigt checkpoint?)", path);
  h5::Id sp(H5Dget_space(ds), H5Sclose, "H5Dget_space", path);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(sp, &n, nullptr);
  std::string text(n, ' ');
  h5::check(H5Dread(ds, H5T_NATIVE_CHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()), "read of 'meta'", path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": corrupt checkpoint metadata: " + e.what());
  }
  if (j.value("format", "") != kFormat) throw std::runtime_error(path + ": not a " + std::string(kFormat) + " file");
  return j;
}

// Serial probe (one rank): does the file open and carry valid metadata?
bool readable(const std::string& path) {
  if (!fs::is_regular_file(path)) return false;
  if (H5Fis_hdf5(path.c_str()) <= 0) return false;
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return false;
  bool ok = true;
  try {
    readMeta(f, path);
  } catch (const std::exception&) {
    ok = false;
  }
  H5Fclose(f);
  return ok;
}

// checkpoint_<step>.h5 files of a directory, newest (highest step) first.
std::vector<std::pair<long, std::string>> listCheckpoints(const std::string& dir) {
  std::vector<std::pair<long, std::string>> out;
  std::error_code ec;
  for (auto& e : fs::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("checkpoint_", 0) != 0 || n.size() < 15 || n.substr(n.size() - 3) != ".h5") continue;
    const std::string num = n.substr(11, n.size() - 14);
    if (num.empty() || !std::all_of(num.begin(), num.end(), ::isdigit)) continue;
    out.emplace_back(std::stol(num), e.path().string());
  }
  std::sort(out.begin(), out.end(), [](auto& a, auto& b) { return a.first > b.first; });
  return out;
}

std::string bcastString(MPI_Comm comm, std::string s) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  unsigned long long n = s.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
  s.resize(n);
  MPI_Bcast(s.data(), int(n), MPI_CHAR, 0, comm);
  return s;
}

} // namespace

Checkpointer::Checkpointer(const Grid& g, std::string dir, int keep) : g_(g), dir_(std::move(dir)), keep_(keep) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

std::string Checkpointer::write(long step, const FieldStore& fields, const nlohmann::json& metaIn) {
  const double w0 = MPI_Wtime();
  const std::string tmp = dir_ + "/checkpoint.h5.tmp";
  char base[40];
  std::snprintf(base, sizeof base, "checkpoint_%09ld.h5", step);
  const std::string final = dir_ + "/" + base;

  nlohmann::json meta = metaIn;
  meta["format"] = kFormat;
  meta["grid"] = {{"cells", g_.n}, {"lo", g_.lo}, {"hi", g_.hi}, {"ranks", g_.size}};
  nlohmann::json fj;
  for (auto& n : fields.allocatedNames()) {
    const auto& d = fields.decls().at(n);
    fj[n] = {{"centring", d.centring == Centring::Node ? "node" : "cell"},
             {"components", d.components},
             {"integer", d.isInt}};
  }
  meta["fields"] = fj;
  // HDF5 metadata writes (the 'effects' attribute, the 'meta' dataset's size) are collective
  // and need the same arguments on every rank. Some values are each rank's own clock
  // (wall_seconds_total, the level set's fm_seconds); an attribute of a different length on
  // each rank made the ranks flush the metadata cache a different number of times, and
  // H5Fclose deadlocked (a 48^3 falling block at 2 ranks, first checkpoint). Write rank 0's.
  meta = nlohmann::json::parse(bcastString(g_.comm, meta.dump()));

  // Every rank must reach the same verdict, or some would wait in a collective.
  std::string err;
  double bytes = 0;
  for (auto& n : fields.allocatedNames()) {
    const auto& d = fields.decls().at(n);
    double pts = 1;
    for (int a = 0; a < 3; ++a) pts *= d.centring == Centring::Node ? g_.nodes(a) : g_.n[a];
    bytes += pts * d.components * (d.isInt ? 4 : 8);
  }
  try {
    h5::requireSpace(g_, dir_, bytes, "cannot write " + tmp);
  } catch (const std::exception& e) {
    throw std::runtime_error("checkpoint of step " + std::to_string(step) + " failed: " + e.what() +
                             " (earlier checkpoints in " + dir_ + " are untouched)");
  }
  try {
    h5::Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate", tmp);
    h5::check(H5Pset_fapl_mpio(fapl, g_.io, MPI_INFO_NULL), "H5Pset_fapl_mpio", tmp);
    h5::Id file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose, "file create", tmp);
    h5::Id dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "H5Pcreate", tmp);
    h5::check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio", tmp);
    const double t = meta.value("t", 0.0);
    const long long st = step;
    writeAttr(file, "time", H5T_NATIVE_DOUBLE, t, tmp);
    writeAttr(file, "step", H5T_NATIVE_LLONG, st, tmp);
    writeStringAttr(file, "format", kFormat, tmp);
    if (meta.contains("effects")) writeStringAttr(file, "effects", meta["effects"].dump(), tmp);
    writeText(file, dxpl, g_, "meta", meta.dump(), tmp);
    h5::Id grp(H5Gcreate2(file, "fields", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "group create", tmp);
    for (auto& n : fields.allocatedNames()) {
      const auto& d = fields.decls().at(n);
      const h5::Box box = ownedBox(g_, d.centring);
      withArrays(fields, n, [&](const auto& arrays) { h5::writeBox(grp, dxpl, g_, n, arrays, box, tmp); });
    }
    grp.close(tmp);
    file.close(tmp);
  } catch (const std::exception& e) {
    err = e.what();
    const std::string why = h5::diagnoseWrite(dir_);
    if (!why.empty()) err += ": " + why;
  }
  int bad = err.empty() ? 0 : 1, anyBad = 0;
  MPI_Allreduce(&bad, &anyBad, 1, MPI_INT, MPI_MAX, g_.comm);
  // Only rank 0 touches names: sync, rename, point `latest`, prune.
  if (g_.rank == 0 && !anyBad) {
    try {
      fsyncPath(tmp, false);
      if (std::rename(tmp.c_str(), final.c_str()) != 0)
        throw std::runtime_error("cannot rename " + tmp + " to " + final + ": " + std::strerror(errno));
      const std::string lt = dir_ + "/latest.tmp", l = dir_ + "/latest";
      {
        std::ofstream o(lt, std::ios::trunc);
        o << base << "\n";
        o.close();
        if (!o) throw std::runtime_error("cannot write " + lt + ": " + std::strerror(errno));
      }
      fsyncPath(lt, false);
      if (std::rename(lt.c_str(), l.c_str()) != 0)
        throw std::runtime_error("cannot rename " + lt + " to " + l + ": " + std::strerror(errno));
      fsyncPath(dir_, true);
      auto all = listCheckpoints(dir_);
      for (size_t i = size_t(std::max(keep_, 1)); i < all.size(); ++i) {
        std::error_code ec;
        fs::remove(all[i].second, ec);
      }
      std::error_code ec;
      bytes_ = (long long)fs::file_size(final, ec);
    } catch (const std::exception& e) {
      err = e.what();
      bad = 1;
    }
  }
  if (anyBad && g_.rank == 0) {
    std::error_code ec;
    fs::remove(tmp, ec);
  }
  MPI_Allreduce(&bad, &anyBad, 1, MPI_INT, MPI_MAX, g_.comm);
  if (anyBad) {
    // Whose message? The lowest failing rank's.
    int who = bad ? g_.rank : g_.size, first = 0;
    MPI_Allreduce(&who, &first, 1, MPI_INT, MPI_MIN, g_.comm);
    std::string msg = err;
    if (first != 0) {
      unsigned long long n = msg.size();
      MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, first, g_.comm);
      msg.resize(n);
      MPI_Bcast(msg.data(), int(n), MPI_CHAR, first, g_.comm);
    } else {
      msg = bcastString(g_.comm, msg);
    }
    throw std::runtime_error("checkpoint of step " + std::to_string(step) + " failed: " + msg +
                             " (earlier checkpoints in " + dir_ + " are untouched)");
  }
  MPI_Bcast(&bytes_, 1, MPI_LONG_LONG, 0, g_.comm);
  seconds_ = MPI_Wtime() - w0;
  return final;
}

std::string findCheckpoint(MPI_Comm comm, const std::string& path) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  std::string found, why;
  if (rank == 0) {
    if (fs::is_regular_file(path)) {
      if (readable(path)) found = path;
      else why = path + " is not a readable Voigt checkpoint";
    } else if (fs::is_directory(path)) {
      std::ifstream l(path + "/latest");
      std::string name;
      if (l >> name && readable(path + "/" + name)) found = path + "/" + name;
      if (found.empty())
        for (auto& [step, p] : listCheckpoints(path))
          if (readable(p)) {
            found = p;
            break;
          }
      if (found.empty()) why = "no readable checkpoint in " + path;
    } else {
      why = "no checkpoint at " + path + " (neither a file nor a directory)";
    }
  }
  found = bcastString(comm, found);
  why = bcastString(comm, why);
  if (found.empty()) throw std::runtime_error("restart: " + why);
  return found;
}

nlohmann::json readCheckpoint(const Grid& g, FieldStore& fields, const std::string& path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  h5::Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate", path);
  h5::check(H5Pset_fapl_mpio(fapl, g.io, MPI_INFO_NULL), "H5Pset_fapl_mpio", path);
  h5::Id file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl), H5Fclose, "file open", path);
  h5::Id dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "H5Pcreate", path);
  h5::check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio", path);
  const nlohmann::json meta = readMeta(file, path);
  const auto cells = meta.at("grid").at("cells").get<std::array<int, 3>>();
  if (cells != g.n)
    throw std::runtime_error(path + ": checkpoint grid is " + std::to_string(cells[0]) + " x " +
                             std::to_string(cells[1]) + " x " + std::to_string(cells[2]) + " cells, the scene's is " +
                             std::to_string(g.n[0]) + " x " + std::to_string(g.n[1]) + " x " +
                             std::to_string(g.n[2]));
  const auto& fj = meta.at("fields");
  h5::Id grp(H5Gopen2(file, "fields", H5P_DEFAULT), H5Gclose, "group open 'fields'", path);
  for (auto& n : fields.allocatedNames()) {
    const auto& d = fields.decls().at(n);
    if (!fj.contains(n) && d.optionalOnRestart) continue; // zero, as allocated
    if (!fj.contains(n))
      throw std::runtime_error(path + ": field '" + n + "' is not in the checkpoint (written by a run with other effects?)");
    const auto& f = fj.at(n);
    if (f.at("components").get<int>() != d.components || f.at("integer").get<bool>() != d.isInt ||
        (f.at("centring").get<std::string>() == "node") != (d.centring == Centring::Node))
      throw std::runtime_error(path + ": field '" + n + "' has a different shape in the checkpoint");
    const h5::Box box = ownedBox(g, d.centring);
    withArrays(fields, n, [&](const auto& arrays) { h5::readBox(grp, dxpl, g, n, arrays, box, path); });
  }
  grp.close(path);
  file.close(path);
  return meta;
}

void truncateOutputs(const std::string& dir, const nlohmann::json& sizes) {
  for (auto& [name, v] : sizes.items()) {
    const std::string path = dir + "/" + name;
    const auto size = v.get<long long>();
    std::error_code ec;
    if (!fs::exists(path, ec)) continue;
    if (size <= 0) fs::remove(path, ec);
    else if ((long long)fs::file_size(path, ec) > size) fs::resize_file(path, std::uintmax_t(size), ec);
    if (ec) throw std::runtime_error("restart: cannot cut " + path + " back to its checkpointed size: " + ec.message());
  }
}

} // namespace voigt
