#include "io/fields_out.hpp"

#include "io/h5_util.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace voigt {
namespace {

using H5Id = h5::Id;
using h5::check;

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
  check(H5Pset_fapl_mpio(fapl, g_.io, MPI_INFO_NULL), "H5Pset_fapl_mpio", path);
  // Free space is checked before the file exists: HDF5 cannot clean up after
  // a write that fails half-way (h5_util.hpp, requireSpace).
  double bytes = 0;
  for (const auto& f : fields)
    bytes += 8.0 * f.comps.size() * (g_.n[0] + 1) * (g_.n[1] + 1) * (g_.n[2] + 1);
  h5::requireSpace(g_, dir_, bytes, "cannot write " + path);
  try {
    H5Id file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose, "H5Fcreate", path);
    H5Id dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "H5Pcreate", path);
    check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio", path);

    {
      H5Id sp(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate", path);
      H5Id at(H5Acreate2(file, "time", H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "attribute create 'time'", path);
      check(H5Awrite(at, H5T_NATIVE_DOUBLE, &time), "attribute write 'time'", path);
    }

    for (const auto& f : fields) {
      h5::Box box;
      writtenRange(g_, f.centring, box.b, box.e);
      for (int d = 0; d < 3; ++d) box.gn[d] = g_.n[d] + (f.centring == Centring::Node ? 1 : 0);
      h5::writeBox(file, dxpl, g_, f.name, f.comps, box, path);
    }
    file.close(path);
  } catch (const std::exception& e) {
    const std::string why = h5::diagnoseWrite(dir_);
    throw std::runtime_error(std::string(e.what()) + (why.empty() ? "" : ": " + why));
  }

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

nlohmann::json FieldWriter::entries() const {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : entries_) {
    nlohmann::json f = nlohmann::json::array();
    for (size_t i = 0; i < e.fields.size(); ++i)
      f.push_back({e.fields[i].first, e.fields[i].second == Centring::Node ? "node" : "cell", e.ncomp[i]});
    out.push_back({{"index", e.index}, {"time", e.time}, {"file", e.file}, {"fields", f}});
  }
  return out;
}

void FieldWriter::restoreEntries(const nlohmann::json& j) {
  entries_.clear();
  for (const auto& x : j) {
    Entry e{x.at("index").get<int>(), x.at("time").get<double>(), x.at("file").get<std::string>(), {}, {}};
    for (const auto& f : x.at("fields")) {
      e.fields.emplace_back(f.at(0).get<std::string>(), f.at(1).get<std::string>() == "node" ? Centring::Node
                                                                                               : Centring::Cell);
      e.ncomp.push_back(f.at(2).get<int>());
    }
    entries_.push_back(std::move(e));
  }
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
