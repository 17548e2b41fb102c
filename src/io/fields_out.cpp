#include "io/fields_out.hpp"

#include <hdf5.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace voigt {
namespace {

// Owns one hid_t and closes it with the matching H5?close on scope exit.
class H5Id {
 public:
  using Closer = herr_t (*)(hid_t);
  H5Id(hid_t id, Closer close, const char* what, const std::string& path) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error(path + ": HDF5 " + what + " failed");
  }
  H5Id(const H5Id&) = delete;
  H5Id& operator=(const H5Id&) = delete;
  ~H5Id() { if (id_ >= 0) close_(id_); }
  operator hid_t() const { return id_; }
  // Explicit close so a failing final flush (H5Fclose) is reported.
  void close(const std::string& path) {
    hid_t id = id_;
    id_ = -1;
    if (close_(id) < 0) throw std::runtime_error(path + ": HDF5 close failed");
  }

 private:
  hid_t id_;
  Closer close_;
};

void check(herr_t e, const char* what, const std::string& path) {
  if (e < 0) throw std::runtime_error(path + ": HDF5 " + what + " failed");
}

// Written index range [b, e) per axis in global indices. Node fields always
// span n+1 nodes: in a periodic axis the rank ending at n also writes node n
// (the periodic image of node 0, present in its ghost layer).
void writtenRange(const Grid& g, Centring c, int b[3], int e[3]) {
  for (int d = 0; d < 3; ++d) {
    b[d] = g.c0[d];
    e[d] = g.c1[d] + (c == Centring::Node && g.c1[d] == g.n[d] ? 1 : 0);
  }
}

// Shortest text that reads back to the same double.
std::string num(double v) {
  char b[32];
  auto r = std::to_chars(b, b + sizeof b, v);
  return std::string(b, r.ptr);
}

std::string xmlEscape(const std::string& in) {
  std::string out;
  for (char ch : in) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

} // namespace

FieldWriter::FieldWriter(const Grid& g, std::string dir) : g_(g), dir_(std::move(dir)) {
  // We report errors by exception; HDF5's own stack dump is noise.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

std::string FieldWriter::write(int index, double time, const std::vector<OutField>& fields) {
  char base[32];
  std::snprintf(base, sizeof base, "fields_%06d.h5", index);
  const std::string path = dir_ + "/" + base;

  for (const auto& f : fields) {
    if (f.comps.size() != 1 && f.comps.size() != 3)
      throw std::runtime_error(path + ": field '" + f.name + "' must have 1 or 3 components");
    if (f.name.empty() || f.name.find('/') != std::string::npos || f.name.find('.') == 0)
      throw std::runtime_error(path + ": invalid field name '" + f.name + "'");
    for (const auto& c : f.comps)
      for (int d = 0; d < 3; ++d)
        if (int(c.extent(d)) < g_.ext[d])
          throw std::runtime_error(path + ": field '" + f.name + "' smaller than the grid arrays");
  }

  H5Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate", path);
  check(H5Pset_fapl_mpio(fapl, g_.comm, MPI_INFO_NULL), "H5Pset_fapl_mpio", path);
  H5Id file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose, "H5Fcreate", path);
  H5Id dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "H5Pcreate", path);
  check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio", path);

  {
    H5Id sp(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate", path);
    H5Id at(H5Acreate2(file, "time", H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
            "attribute create 'time'", path);
    check(H5Awrite(at, H5T_NATIVE_DOUBLE, &time), "attribute write 'time'", path);
  }

  using Packed = Kokkos::View<double****, Kokkos::LayoutRight, MemSpace>;
  for (const auto& f : fields) {
    const int nc = int(f.comps.size());
    int b[3], e[3];
    writtenRange(g_, f.centring, b, e);
    const int extra = f.centring == Centring::Node ? 1 : 0;
    // Dataset and hyperslab in C order (z, y, x[, comp]).
    hsize_t gdims[4] = {hsize_t(g_.n[2] + extra), hsize_t(g_.n[1] + extra),
                        hsize_t(g_.n[0] + extra), hsize_t(nc)};
    hsize_t start[4] = {hsize_t(b[2]), hsize_t(b[1]), hsize_t(b[0]), 0};
    hsize_t count[4] = {hsize_t(e[2] - b[2]), hsize_t(e[1] - b[1]), hsize_t(e[0] - b[0]), hsize_t(nc)};
    const int rank = nc == 1 ? 3 : 4;
    const bool empty = count[0] * count[1] * count[2] == 0;

    // Pack owned points on the execution space, then one copy to the host.
    Packed buf("io::packed", count[0], count[1], count[2], nc);
    const int lb[3] = {g_.local(0, b[0]), g_.local(1, b[1]), g_.local(2, b[2])};
    const int le[3] = {g_.local(0, e[0]), g_.local(1, e[1]), g_.local(2, e[2])};
    for (int c = 0; c < nc && !empty; ++c) {
      const Field src = f.comps[c];
      const int bx = lb[0], by = lb[1], bz = lb[2];
      Kokkos::parallel_for("io::pack", Policy3({lb[0], lb[1], lb[2]}, {le[0], le[1], le[2]}),
                           KOKKOS_LAMBDA(int i, int j, int k) {
                             buf(k - bz, j - by, i - bx, c) = src(i, j, k);
                           });
    }
    auto host = Kokkos::create_mirror_view(buf);
    Kokkos::deep_copy(host, buf);

    H5Id fspace(H5Screate_simple(rank, gdims, nullptr), H5Sclose, "H5Screate_simple", path);
    H5Id dset(H5Dcreate2(file, f.name.c_str(), H5T_IEEE_F64LE, fspace, H5P_DEFAULT, H5P_DEFAULT,
                         H5P_DEFAULT),
              H5Dclose, ("dataset create '" + f.name + "'").c_str(), path);
    hsize_t mdims[4] = {std::max<hsize_t>(count[0], 1), std::max<hsize_t>(count[1], 1),
                        std::max<hsize_t>(count[2], 1), hsize_t(nc)};
    H5Id mspace(H5Screate_simple(rank, mdims, nullptr), H5Sclose, "H5Screate_simple", path);
    if (empty) {
      // Still take part in the collective write.
      check(H5Sselect_none(fspace), "H5Sselect_none", path);
      check(H5Sselect_none(mspace), "H5Sselect_none", path);
    } else {
      check(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr),
            "H5Sselect_hyperslab", path);
    }
    check(H5Dwrite(dset, H5T_NATIVE_DOUBLE, mspace, fspace, dxpl, host.data()),
          ("write of '" + f.name + "'").c_str(), path);
  }
  file.close(path);

  Entry en{index, time, base, {}, {}};
  for (const auto& f : fields) {
    en.fields.emplace_back(f.name, f.centring);
    en.ncomp.push_back(int(f.comps.size()));
  }
  auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& x) { return x.index == index; });
  if (it != entries_.end()) *it = std::move(en);
  else entries_.push_back(std::move(en));
  std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) { return a.index < b.index; });
  if (g_.rank == 0) writeXdmf();
  return path;
}

void FieldWriter::writeXdmf() const {
  const auto& n = g_.n;
  auto dims = [&](int extra) {
    return std::to_string(n[2] + extra) + " " + std::to_string(n[1] + extra) + " " +
           std::to_string(n[0] + extra);
  };
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    << "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n<Domain>\n"
    << "<Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& e : entries_) {
    x << " <Grid Name=\"" << e.file << "\" GridType=\"Uniform\">\n"
      << "  <Time Value=\"" << num(e.time) << "\"/>\n"
      << "  <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << dims(1) << "\"/>\n"
      << "  <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
      << "   <DataItem Name=\"Origin\" Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" "
         "Format=\"XML\">"
      << num(g_.lo[2]) << " " << num(g_.lo[1]) << " " << num(g_.lo[0]) << "</DataItem>\n"
      << "   <DataItem Name=\"Spacing\" Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" "
         "Format=\"XML\">"
      << num(g_.h[2]) << " " << num(g_.h[1]) << " " << num(g_.h[0]) << "</DataItem>\n"
      << "  </Geometry>\n";
    for (size_t i = 0; i < e.fields.size(); ++i) {
      const bool node = e.fields[i].second == Centring::Node;
      const bool vec = e.ncomp[i] == 3;
      const std::string name = xmlEscape(e.fields[i].first);
      x << "  <Attribute Name=\"" << name << "\" AttributeType=\"" << (vec ? "Vector" : "Scalar")
        << "\" Center=\"" << (node ? "Node" : "Cell") << "\">\n"
        << "   <DataItem Dimensions=\"" << dims(node ? 1 : 0) << (vec ? " 3" : "")
        << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << e.file << ":/" << name
        << "</DataItem>\n  </Attribute>\n";
    }
    x << " </Grid>\n";
  }
  x << "</Grid>\n</Domain>\n</Xdmf>\n";

  // Write-then-rename so a reader (ParaView polling) never sees half a file.
  const std::string path = dir_ + "/fields.xdmf", tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << x.str();
    out.close();
    if (!out) throw std::runtime_error(tmp + ": cannot write XDMF");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error(path + ": cannot rename " + tmp);
}

} // namespace voigt
