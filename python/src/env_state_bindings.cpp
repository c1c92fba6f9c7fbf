// python: what gpfd._core.EnvBatch adds for pickling (__getstate__, __setstate__: copy.deepcopy
// and pickle, mid-episode, bit for bit) and for drawing Tetris (tetris_board;
// gpfd/environments/render.py draws the rest from the state variables). Added to the class that
// env_bindings.cpp binds.
#include <fmt/format.h>
#include <nanobind/stl/map.h>
#include <nanobind/stl/string.h>

#include <cstdint>
#include <vector>

#include "bindings.hpp"
#include "env_batch.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/env/tetromino.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::python {
namespace {

const char* autoresetName(Autoreset mode) {
  switch (mode) {
    case Autoreset::SameStep:
      return "same_step";
    case Autoreset::Disabled:
      return "disabled";
    case Autoreset::NextStep:
      break;
  }
  return "next_step";
}

// Words as bytes, little-endian whatever the host, and back.
nb::bytes toBytes(const std::vector<std::uint64_t>& words) {
  std::string bytes(words.size() * 8, '\0');
  for (std::size_t i = 0; i < words.size(); ++i) {
    for (std::size_t b = 0; b < 8; ++b) bytes[8 * i + b] = static_cast<char>(words[i] >> (8 * b));
  }
  return nb::bytes(bytes.data(), bytes.size());
}

std::vector<std::uint64_t> fromBytes(const nb::bytes& bytes, const std::string& where) {
  if (bytes.size() % 8 != 0) {
    throw InputError(fmt::format("a snapshot is whole 64-bit words, got {} bytes", bytes.size()),
                     where);
  }
  const auto* data = static_cast<const unsigned char*>(bytes.data());
  std::vector<std::uint64_t> words(bytes.size() / 8, 0);
  for (std::size_t i = 0; i < words.size(); ++i) {
    for (std::size_t b = 0; b < 8; ++b) words[i] |= std::uint64_t{data[8 * i + b]} << (8 * b);
  }
  return words;
}

// (name, params, num_envs, autoreset, engine, snapshot): what __setstate__ makes the batch from.
// TypeError (what pickle and copy expect of what cannot be pickled) for an environment without
// snapshots.
nb::tuple getState(const EnvBatch& batch) {
  std::vector<std::uint64_t> words;
  try {
    words = batch.snapshot();
  } catch (const InputError& e) {
    throw nb::type_error(("cannot pickle gpfd's environment: " + e.message()).c_str());
  }
  return nb::make_tuple(batch.prototype().name(), batch.prototype().params(), batch.size(),
                        autoresetName(batch.autoreset()), batch.batched() ? "batched" : "loop",
                        toBytes(words));
}

void setState(EnvBatch& self, const nb::tuple& state) {
  if (state.size() != 6) throw InputError("not a pickled gpfd EnvBatch", "EnvBatch.__setstate__");
  const auto name = nb::cast<std::string>(state[0]);
  const auto params = paramsFromDict(nb::cast<nb::dict>(state[1]), name);
  const auto words = fromBytes(nb::cast<nb::bytes>(state[5]), name + " snapshot");
  new (&self) EnvBatch(name, params, nb::cast<std::size_t>(state[2]),
                       parseAutoreset(nb::cast<std::string>(state[3])),
                       parseEngine(nb::cast<std::string>(state[4])));
  try {
    self.restore(words);
  } catch (...) {
    self.~EnvBatch();  // nanobind treats the instance as not constructed when this throws.
    throw;
  }
}

// Tetris' board of instance i: cells (rows x cols, bool, row 0 at the bottom; the hidden rows above
// the top are left out), the current piece (0..6 = IOTSZLJ) with the cells of its first
// orientation (4 x 2: x to the right, y up), and whether the game is over.
nb::dict tetrisBoard(const EnvBatch& batch, std::size_t i) {
  const auto* tetris = dynamic_cast<const env::Tetris*>(batch.scalarInstance(i));
  if (tetris == nullptr) throw InputError("a Tetris board exists for Tetris only", "tetris_board");
  const env::TetrisBoard& board = tetris->board();
  const auto rows = static_cast<std::size_t>(board.rows());
  const auto cols = static_cast<std::size_t>(board.cols());
  auto cells = newArray<bool>({rows, cols});
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < cols; ++c) {
      cells.data()[r * cols + c] = board.filled(static_cast<int>(r), static_cast<int>(c));
    }
  }
  auto pieceCells = newArray<std::int64_t>({4, 2});
  const env::Orientation& first = env::orientationsOf(tetris->piece()).front();
  for (std::size_t k = 0; k < 4; ++k) {
    pieceCells.data()[2 * k] = first.cells[k][0];
    pieceCells.data()[2 * k + 1] = first.cells[k][1];
  }
  nb::dict out;
  out["cells"] = cells;
  out["piece"] = tetris->piece();
  out["piece_cells"] = pieceCells;
  out["game_over"] = tetris->gameOver();
  return out;
}

}  // namespace

void bindEnvironmentState(nb::module_& m) {
  const nb::handle cls = m.attr("EnvBatch");
  nb::cpp_function_def(&getState, nb::scope(cls), nb::name("__getstate__"), nb::is_method());
  nb::cpp_function_def(&setState, nb::scope(cls), nb::name("__setstate__"), nb::is_method(),
                       nb::arg("state"));
  nb::cpp_function_def(&tetrisBoard, nb::scope(cls), nb::name("tetris_board"), nb::is_method(),
                       nb::arg("index") = 0,
                       "Tetris: instance index's board (rows x cols, row 0 at the bottom), its "
                       "piece with the cells of the piece's first orientation, and game over.");
}

}  // namespace gpfd::python
