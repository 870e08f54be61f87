// `glintlab eval --model NAME [--param k=v ...]`: any registered model on CSV query rows or a grid
// of directions, batched (core/simd/model_batch.h).
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "cli/batch_options.h"
#include "core/model_layout.h"
#include "core/model_registry.h"

namespace glintlab::cli {

struct ModelEvalArgs {
  std::string model;
  std::vector<std::string> params;  // the raw "k=v" texts of --param
  std::string in_path;              // --in, or empty with --grid
  std::string grid;                 // --grid, or empty
  std::string query;                // --query (with --grid): name=value,... of the needed columns
  bool query_given = false;
  std::string out_path;
  BatchOptionTexts batch;
};

void run_model_eval(const ModelEvalArgs& args);

// The checks eval --model makes on every query row before evaluating it, shared with sample
// --model: each value finite, unit wi and wo (and the corner vectors where the model reads them),
// the light's range, and the model's own rules (its static validate, core/model.h).
// `at(column)` names where a column's value came from ("" = the row) for the message.
void check_query_row(const ModelEntry& model, const QueryRow<double>& row,
                     const std::function<std::string(std::string_view column)>& at);
// The query columns besides wi and wo that `model` needs (footprint, light, corners), in layout
// order.
std::vector<std::string_view> needed_query_columns(const ModelEntry& model);
// The query row of --query 'name=value,...' (`given`: whether the option was on the command
// line), shared by sample --model and eval --model --grid: each column of needed_query_columns
// given once and no other, every other column the layout's default (wi = wo = the normal).
// Throws InputError naming the columns missing or not needed; the caller sets the directions and
// runs check_query_row.
QueryRow<double> parse_query_option(const ModelEntry& model, const std::string& text, bool given);

// The help text of the --model form (appended to eval's footer).
extern const char* const kModelEvalFooter;

}  // namespace glintlab::cli
