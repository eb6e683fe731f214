// Reads the numeric CSV tables of refdata/beam (comment lines start with '#', one header line).
#pragma once

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace beam_test {

inline std::string refdata_dir() {
  return std::string(TFMB_SOURCE_DIR) + "/refdata/beam";
}

/// Columns by header name; non-numeric fields become NaN, raw strings are kept in `text`.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::vector<std::vector<std::string>> text;
  int col(const std::string& name) const {
    for (size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    throw std::runtime_error("no column " + name);
  }
};

inline std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false;
  for (char ch : line) {
    if (ch == '"') {
      quoted = !quoted;
    } else if (ch == ',' && !quoted) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += ch;
    }
  }
  out.push_back(cur);
  return out;
}

inline Table read_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  Table t;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    auto f = split_csv(line);
    if (t.header.empty()) {
      t.header = f;
      continue;
    }
    std::vector<double> v;
    for (auto& s : f) {
      try {
        size_t pos = 0;
        double d = std::stod(s, &pos);
        v.push_back(pos == s.size() ? d : std::numeric_limits<double>::quiet_NaN());
      } catch (...) {
        v.push_back(std::numeric_limits<double>::quiet_NaN());
      }
    }
    t.rows.push_back(v);
    t.text.push_back(f);
  }
  return t;
}

}  // namespace beam_test
