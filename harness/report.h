// Suite outputs: results.json (machines), results.js (the same, loadable from file://),
// junit.xml (CI), index.html + report.js + report.css (people), and per-image files under img/.
#pragma once
#include <string>
#include <vector>

#include "harness/suite.h"

namespace gib {

nlohmann::json row_to_json(const ResultRow& row);
nlohmann::json suite_to_json(const SuiteResult& suite);
nlohmann::json cases_to_json(const std::vector<Case>& cases);  // the report's "cases"
void write_suite_outputs(const std::string& out_dir, const SuiteResult& suite, const std::vector<Case>& cases);
// results.json, results.js, junit.xml and the HTML report from a suite's JSON (suite_to_json
// plus "cases"): one writer for `run` and for `merge`.
void write_report_files(const std::string& out_dir, const nlohmann::json& j);
// The results table on stdout, from a suite's JSON (rows not run: one line each, no messages).
void print_suite_table(const nlohmann::json& j);
// <stem>.png (sRGB preview, exposure 0) and <stem>.js (float data for the report's exposure
// control: window.GIB_IMG[id] = {w, h, data: base64 float32 RGB}).
void write_report_image(const std::string& stem, const FloatImage& img);
void write_report_error_map(const std::string& stem, const FloatImage& error_map);  // <stem>.png, magma
std::string base64(const void* data, size_t bytes);

}  // namespace gib
