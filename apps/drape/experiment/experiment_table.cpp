#include "experiment_table.hpp"

#include <drape/io/atomic_file.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace drape::cli {
namespace {

const ExperimentColumn& column(const std::string& name) {
  for (const auto& c : experiment_columns())
    if (c.name == name) return c;
  throw Error("unknown experiment column '" + name + "'");
}

// Three significant digits, in plain notation where that stays short.
std::string number(double v) {
  char b[32];
  const double a = std::fabs(v);
  if (v == 0)
    std::snprintf(b, sizeof b, "0");
  else if (a >= 1e-2 && a < 1e5)
    std::snprintf(b, sizeof b, "%.3g", v);
  else
    std::snprintf(b, sizeof b, "%.2e", v);
  return b;
}

std::string header(const std::string& name, const std::string& unit) {
  const ExperimentColumn& c = column(name);
  const std::string u = name == "infer" ? unit : c.unit;
  return u.empty() ? c.header : c.header + " (" + u + ")";
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

}  // namespace

std::string table_markdown(const ExperimentTable& t) {
  std::ostringstream o;
  o << "## " << t.title << "\n\n";
  if (!t.note.empty()) o << t.note << "\n\n";
  if (!t.setup.empty()) o << t.setup << "\n\n";
  o << "Each cell: ours / the seed's (— where the seed has no number or the column does not apply); a column marked "
       "* holds ours alone, because the seed's number there is another quantity (below the table).\n\n| row |";
  for (const auto& c : t.columns) o << " " << header(c, "") << (column(c).not_as_the_seed ? " *" : "") << " |";
  o << "\n|---|";
  for (std::size_t i = 0; i < t.columns.size(); ++i) o << "---|";
  o << "\n";
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    o << "| " << row.name << " |";
    for (const auto& c : t.columns) {
      const auto ours = row.values.find(c);
      const auto seed = t.seed[r].find(c);
      // (A value not measured for any body -- an optimize row whose drapes are all "not results" -- is NaN: no number.)
      const bool measured = ours != row.values.end() && std::isfinite(ours->second);
      std::string cell = measured ? number(ours->second) : "—";
      if (c == "infer" && measured) cell += " " + row.infer_unit;
      if (!column(c).not_as_the_seed) {
        cell += " / ";
        cell += seed == t.seed[r].end() ? "—" : number(seed->second);
      }
      o << " " << cell << " |";
    }
    o << "\n";
  }
  // The seed's numbers of the columns that do not compare, apart, with why.
  for (const auto& c : t.columns) {
    const ExperimentColumn& col = column(c);
    if (!col.not_as_the_seed) continue;
    std::string values;
    for (std::size_t r = 0; r < t.rows.size(); ++r)
      if (const auto seed = t.seed[r].find(c); seed != t.seed[r].end())
        values += (values.empty() ? "" : ", ") + t.rows[r].name + " " + number(seed->second);
    // (Said whether or not the seed gives numbers here: the * promises it below the table.)
    if (values.empty())
      o << "\n* " << col.header << " holds ours alone: the seed's " << col.header << " is another quantity: " << col.not_as_the_seed << ".\n";
    else
      o << "\n* The seed's " << col.header << " (" << values << ") does not compare with ours: " << col.not_as_the_seed << ".\n";
  }
  o << "\nColumns: ";
  for (std::size_t i = 0; i < t.columns.size(); ++i) {
    const auto& c = column(t.columns[i]);
    o << (i ? "; " : "") << c.header << ": " << c.doc;
  }
  o << ".\n";
  return o.str();
}

std::string table_csv(const ExperimentTable& t) {
  std::ostringstream o;
  o << "row";
  for (const auto& c : t.columns) o << "," << c << "," << c << "_seed";
  o << ",infer_unit,provenance\n";
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    o << csv_field(row.name);
    for (const auto& c : t.columns) {
      const auto ours = row.values.find(c);
      const auto seed = t.seed[r].find(c);
      char b[40];
      o << ",";
      if (ours != row.values.end() && std::isfinite(ours->second)) {
        std::snprintf(b, sizeof b, "%.9g", ours->second);
        o << b;
      }
      o << ",";
      if (seed != t.seed[r].end()) {
        std::snprintf(b, sizeof b, "%.9g", seed->second);
        o << b;
      }
    }
    o << "," << row.infer_unit << "," << csv_field(row.provenance) << "\n";
  }
  return o.str();
}

void write_table(const ExperimentTable& table, const std::filesystem::path& dir) {
  write_text_atomically(dir / "table.md", table_markdown(table));
  write_text_atomically(dir / "table.csv", table_csv(table));
}

}  // namespace drape::cli
