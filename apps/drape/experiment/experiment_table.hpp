#pragma once
// The result of an experiment: one row per entry of the file, our value and the
// seed's for each column, written as Markdown (for docs/results.md) and CSV.
#include <drape/experiment/experiment.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace drape::cli {

struct ExperimentTableRow {
  std::string name;
  std::map<std::string, double> values;  // by column; absent: does not apply to this row
  std::string infer_unit;                // "ms" or "s" for the infer column
  std::string provenance;                // the files the values come from
};

struct ExperimentTable {
  std::string title, note, setup;  // setup: datasets, scale, training, machine
  std::vector<std::string> columns;
  std::vector<ExperimentTableRow> rows;
  std::vector<std::map<std::string, double>> seed;  // parallel to rows
};

std::string table_markdown(const ExperimentTable& table);
std::string table_csv(const ExperimentTable& table);
// Writes <dir>/table.md and <dir>/table.csv atomically.
void write_table(const ExperimentTable& table, const std::filesystem::path& dir);

}  // namespace drape::cli
