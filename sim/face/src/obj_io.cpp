#include "facectl/face/obj_io.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "facectl/face/input_error.hpp"

namespace facectl::face {
namespace {

double parse_double(const std::string& tok, const std::string& path, int line) {
  const char* s = tok.c_str();
  char* end = nullptr;
  errno = 0;
  double d = std::strtod(s, &end);
  // strtod takes "nan" and "inf"; a vertex there has no place on a face.
  if (end == s || *end != '\0' || errno == ERANGE || !std::isfinite(d))
    throw InputError(path, line, 0, "expected a finite number, found '" + tok + "'");
  return d;
}

int parse_index(const std::string& tok, int nverts, const std::string& path, int line) {
  std::string head = tok.substr(0, tok.find('/'));
  char* end = nullptr;
  long i = std::strtol(head.c_str(), &end, 10);
  if (head.empty() || *end != '\0')
    throw InputError(path, line, 0, "expected a vertex index, found '" + tok + "'");
  long idx = i > 0 ? i - 1 : nverts + i;  // negative indices are relative
  if (i == 0 || idx < 0 || idx >= nverts)
    throw InputError(path, line, 0,
                     "vertex index " + head + " out of range 1.." + std::to_string(nverts));
  return static_cast<int>(idx);
}

}  // namespace

TriMesh read_obj(const std::string& path, double scale) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file");
  TriMesh m;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    std::istringstream ss(text);
    std::string tag;
    if (!(ss >> tag) || tag[0] == '#') continue;
    std::vector<std::string> tok;
    for (std::string t; ss >> t;) tok.push_back(t);
    if (tag == "v") {
      if (tok.size() < 3)
        throw InputError(path, line, 0,
                         "expected 'v x y z', found " + std::to_string(tok.size()) + " values");
      m.v.push_back(Vec3(parse_double(tok[0], path, line), parse_double(tok[1], path, line),
                         parse_double(tok[2], path, line)) *
                    scale);
    } else if (tag == "f") {
      if (tok.size() < 3)
        throw InputError(
            path, line, 0,
            "expected a face with at least 3 vertices, found " + std::to_string(tok.size()));
      int n = static_cast<int>(m.v.size());
      std::vector<int> idx;
      for (const auto& t : tok) idx.push_back(parse_index(t, n, path, line));
      for (std::size_t k = 1; k + 1 < idx.size(); ++k)
        m.tris.push_back({idx[0], idx[k], idx[k + 1]});
    }
    // vt, vn, mtllib, usemtl, o, g, s: not needed by the model.
  }
  if (m.tris.empty()) throw InputError(path + ": expected at least one face ('f'), found none");
  return m;
}

void write_obj(const std::string& path, const TriMesh& mesh, double scale) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot open file for writing");
  out.precision(9);
  out << "# written by facectl\n";
  for (std::size_t i = 0; i < mesh.v.size(); ++i)
    out << "v " << mesh.v.x[i] / scale << ' ' << mesh.v.y[i] / scale << ' ' << mesh.v.z[i] / scale
        << '\n';
  for (const Tri& t : mesh.tris)
    out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  if (!out) throw InputError(path + ": write failed");
}

}  // namespace facectl::face
