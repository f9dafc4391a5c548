#include "support/nrrd_reader.h"

#include <zlib.h>

#include <fstream>
#include <iterator>
#include <sstream>

namespace scansurf::test {
namespace {

std::string gunzip(const std::string& data) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) return {};
  std::string out;
  char buf[1 << 15];
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  int rc;
  do {
    z.next_out = reinterpret_cast<Bytef*>(buf);
    z.avail_out = sizeof buf;
    rc = inflate(&z, Z_NO_FLUSH);
    out.append(buf, sizeof buf - z.avail_out);
  } while (rc == Z_OK);
  inflateEnd(&z);
  return rc == Z_STREAM_END ? out : std::string();
}

}  // namespace

Nrrd readNrrd(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::size_t end = bytes.find("\n\n");
  Nrrd n;
  if (end == std::string::npos || bytes.rfind("NRRD0004\n", 0) != 0) return n;
  std::istringstream in(bytes.substr(0, end));
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t kv = line.find(":=");
    const std::size_t colon = line.find(": ");
    if (kv != std::string::npos && (colon == std::string::npos || kv < colon))
      n.fields[line.substr(0, kv)] = line.substr(kv + 2);
    else if (colon != std::string::npos)
      n.fields[line.substr(0, colon)] = line.substr(colon + 2);
  }
  n.data = gunzip(bytes.substr(end + 2));
  return n;
}

std::vector<double> nrrdNumbers(std::string field) {
  for (char& c : field)
    if (c == '(' || c == ')' || c == ',') c = ' ';
  std::istringstream in(field);
  std::vector<double> out;
  std::string token;
  while (in >> token)
    if (token != "none") out.push_back(std::stod(token));
  return out;
}

}  // namespace scansurf::test
