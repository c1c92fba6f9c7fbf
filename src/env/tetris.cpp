#include "gpfd/env/tetris.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "gpfd/env/common_params.hpp"
#include "gpfd/env/snapshot.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {

const ParamTable<TetrisConfig>& TetrisConfig::table() {
  static const auto table = [] {
    ParamTable<TetrisConfig> t("tetris");
    t.integer(
         "rows", [](auto& c) -> auto& { return c.rows; }, 4, TetrisBoard::kMaxRows,
         "board height (the paper: 12; the literature: 20)")
        .integer(
            "cols", [](auto& c) -> auto& { return c.cols; }, 4, TetrisBoard::kMaxCols,
            "board width (the paper: 8; the literature: 10)")
        .choice(
            "state", [](auto& c) -> auto& { return c.state; },
            std::vector<std::pair<std::string, TetrisFeatures>>{
                {"paper", TetrisFeatures::Paper}, {"bertsekas", TetrisFeatures::Bertsekas}},
            "paper: heights, |differences|, max height, holes, piece 0-6 = IOTSZLJ; bertsekas: "
            "the same with a constant 1 instead of the piece");
    declareTimeLimit(
        t, "max_steps", [](auto& c) -> auto& { return c.maxSteps; }, "pieces");
    return t;
  }();
  return table;
}

EnvInfo Tetris::info() {
  return {"tetris", "Tetris with the 7 tetrominoes; reward = rows removed (the paper: 12 x 8)",
          TetrisConfig::table().specs(),
          [](const Params& p) { return std::make_unique<Tetris>(TetrisConfig::fromParams(p)); },
          "lpi"};
}

Tetris::Tetris(TetrisConfig config) : config_(config), board_(config.rows, config.cols) {
  for (int c = 1; c <= config_.cols; ++c) names_.push_back(fmt::format("h{}", c));
  for (int c = 1; c < config_.cols; ++c) names_.push_back(fmt::format("d{}", c));
  names_.push_back("max_height");
  names_.push_back("holes");
  names_.push_back(config_.state == TetrisFeatures::Paper ? "piece" : "const");
  state_.assign(names_.size(), 0.0);
  refreshState();
}

ActionSpace Tetris::actionSpace() const {
  ActionSpace space;
  space.kind = ActionSpace::Kind::Discrete;
  space.components = 2;
  space.choices = {kMaxOrientations, config_.cols};
  space.names = {"orientation", "column"};
  return space;
}

void Tetris::refreshState() { board_.features(config_.state, piece_, state_.data()); }

void Tetris::reset(Rng& rng) {
  pieces_.reseed(rng());
  board_.clear();
  piece_ = static_cast<int>(pieces_.below(kPieceCount));
  gameOver_ = false;
  steps_ = 0;
  refreshState();
}

void Tetris::setBoard(const TetrisBoard& board, int piece) {
  if (board.rows() != config_.rows || board.cols() != config_.cols) {
    throw InputError(fmt::format("the board must be {}x{}, got {}x{}", config_.rows, config_.cols,
                                 board.rows(), board.cols()),
                     "tetris board");
  }
  if (piece < 0 || piece >= kPieceCount) {
    throw InputError(fmt::format("a piece is 0..6, got {}", piece), "tetris piece");
  }
  board_ = board;
  piece_ = piece;
  gameOver_ = false;
  steps_ = 0;
  refreshState();
}

void Tetris::setState(std::span<const double> state) {
  const int cols = config_.cols, rows = config_.rows;
  if (state.size() != state_.size()) {
    throw InputError(
        fmt::format("tetris takes {} state variables, got {}", state_.size(), state.size()),
        "tetris state");
  }
  const auto integerAt = [&](std::size_t i, int lo, int hi) {
    const double v = state[i];
    if (!(v >= lo && v <= hi) || v != std::floor(v)) {
      throw InputError(
          fmt::format("{} must be an integer in [{}, {}], got {}", names_[i], lo, hi, v),
          "tetris state");
    }
    return static_cast<int>(v);
  };
  std::vector<int> heights(static_cast<std::size_t>(cols));
  int maxHeight = 0, carvable = 0;
  for (int c = 0; c < cols; ++c) {
    heights[static_cast<std::size_t>(c)] = integerAt(static_cast<std::size_t>(c), 0, rows);
    maxHeight = std::max(maxHeight, heights[static_cast<std::size_t>(c)]);
    carvable += std::max(0, heights[static_cast<std::size_t>(c)] - 1);
  }
  for (int c = 0; c + 1 < cols; ++c) {
    const int d = integerAt(static_cast<std::size_t>(cols + c), 0, rows);
    if (d !=
        std::abs(heights[static_cast<std::size_t>(c)] - heights[static_cast<std::size_t>(c + 1)])) {
      throw InputError(fmt::format("{} must equal |h{} - h{}|",
                                   names_[static_cast<std::size_t>(cols + c)], c + 1, c + 2),
                       "tetris state");
    }
  }
  if (integerAt(static_cast<std::size_t>(2 * cols - 1), 0, rows) != maxHeight) {
    throw InputError("max_height must equal the largest height", "tetris state");
  }
  const int holes = integerAt(static_cast<std::size_t>(2 * cols), 0, carvable);
  int piece = piece_;
  if (config_.state == TetrisFeatures::Paper) {
    piece = integerAt(static_cast<std::size_t>(2 * cols + 1), 0, kPieceCount - 1);
  } else if (state[static_cast<std::size_t>(2 * cols + 1)] != 1.0) {
    throw InputError("const must be 1", "tetris state");
  }
  TetrisBoard board(rows, cols);
  for (int c = 0; c < cols; ++c) {
    for (int r = 0; r < heights[static_cast<std::size_t>(c)]; ++r) board.set(r, c, true);
  }
  int carved = 0;
  for (int r = 0; r < rows && carved < holes; ++r) {
    for (int c = 0; c < cols && carved < holes; ++c) {
      if (r < heights[static_cast<std::size_t>(c)] - 1) {
        board.set(r, c, false);
        ++carved;
      }
    }
  }
  setBoard(board, piece);
}

std::vector<std::uint64_t> Tetris::snapshot() const {
  SnapshotWriter out(name());
  out.integer(config_.rows).integer(config_.cols);
  for (int r = 0; r < board_.storedRows(); ++r) out.word(board_.rowBits(r));
  out.integer(piece_).integer(gameOver_ ? 1 : 0).integer(steps_).rng(pieces_);
  return out.take();
}

void Tetris::restore(std::span<const std::uint64_t> words) {
  SnapshotReader in(name(), words);
  in.integer(config_.rows, config_.rows, "rows");
  in.integer(config_.cols, config_.cols, "cols");
  TetrisBoard board(config_.rows, config_.cols);
  for (int r = 0; r < board.storedRows(); ++r) {
    // At most fullRow(): no cell beyond the last column.
    board.setRowBits(r, static_cast<std::uint32_t>(in.integer(0, board.fullRow(), "a row")));
  }
  const auto piece = static_cast<int>(in.integer(0, kPieceCount - 1, "the piece"));
  const bool gameOver = in.integer(0, 1, "game over") == 1;
  const auto steps = static_cast<int>(in.integer(0, std::numeric_limits<int>::max(), "steps"));
  const Rng::State pieces = in.rng();
  in.finish();
  board_ = board;
  piece_ = piece;
  gameOver_ = gameOver;
  steps_ = steps;
  pieces_.setState(pieces);
  refreshState();
}

void Tetris::checkAction(std::span<const double> action) const {
  if (action.size() != 2) {
    throw InputError(fmt::format("tetris takes 2 action components (orientation, column), got {}",
                                 action.size()),
                     "tetris action");
  }
  const auto orientations = orientationsOf(piece_);
  const double o = action[0], c = action[1];
  if (!(o >= 0 && o < static_cast<double>(orientations.size())) || o != std::floor(o)) {
    throw InputError(
        fmt::format("piece {} has orientations 0..{}, got {}",
                    kPieceLetters[static_cast<std::size_t>(piece_)], orientations.size() - 1, o),
        "tetris action");
  }
  const int width = orientations[static_cast<std::size_t>(o)].width;
  if (!(c >= 0 && c <= config_.cols - width) || c != std::floor(c)) {
    throw InputError(
        fmt::format("orientation {} of piece {} fits columns 0..{}, got {}", o,
                    kPieceLetters[static_cast<std::size_t>(piece_)], config_.cols - width, c),
        "tetris action");
  }
}

StepResult Tetris::step(std::span<const double> action) {
  StepResult result;
  if (gameOver_) {
    result.terminated = true;
    return result;
  }
  checkAction(action);
  const DropOutcome outcome =
      board_.drop(piece_, static_cast<int>(action[0]), static_cast<int>(action[1]));
  ++steps_;
  result.reward = outcome.rowsRemoved;
  gameOver_ = outcome.gameOver;
  result.terminated = gameOver_;
  if (!gameOver_) piece_ = static_cast<int>(pieces_.below(kPieceCount));
  result.truncated = config_.maxSteps > 0 && steps_ >= config_.maxSteps;
  refreshState();
  return result;
}

void Tetris::sampleAction(Rng& rng, std::span<double> action) const {
  auto pick =
      static_cast<int>(rng.below(static_cast<std::uint64_t>(placementCount(piece_, config_.cols))));
  const auto orientations = orientationsOf(piece_);
  for (std::size_t o = 0; o < orientations.size(); ++o) {
    const int columns = config_.cols - orientations[o].width + 1;
    if (pick < columns) {
      action[0] = static_cast<double>(o);
      action[1] = pick;
      return;
    }
    pick -= columns;
  }
}

void Tetris::legalActionMask(std::span<std::uint8_t> mask) const {
  const auto cols = static_cast<std::size_t>(config_.cols);
  if (mask.size() != static_cast<std::size_t>(kMaxOrientations) * cols) {
    throw InputError(fmt::format("tetris has {} x {} actions, got a mask of {}", kMaxOrientations,
                                 cols, mask.size()),
                     "tetris action mask");
  }
  std::fill(mask.begin(), mask.end(), std::uint8_t{0});
  const auto orientations = orientationsOf(piece_);
  for (std::size_t o = 0; o < orientations.size(); ++o) {
    const auto width = static_cast<std::size_t>(orientations[o].width);
    std::fill_n(mask.begin() + static_cast<std::ptrdiff_t>(o * cols), cols - width + 1,
                std::uint8_t{1});
  }
}

void Tetris::nearestLegalAction(std::span<const double> action, std::span<double> legal) const {
  const auto orientations = orientationsOf(piece_);
  const double orientation = std::fmod(action[0], static_cast<double>(orientations.size()));
  const int width = orientations[static_cast<std::size_t>(orientation)].width;
  legal[0] = orientation;
  legal[1] = std::min(action[1], static_cast<double>(config_.cols - width));
}

void Tetris::afterstatesReference(TetrisAfterstates& out) const {
  const int count = placementCount(piece_, config_.cols);
  const std::size_t dim = state_.size();
  out.featureDim = dim;
  out.placements.resize(static_cast<std::size_t>(count));
  out.features.resize(static_cast<std::size_t>(count) * dim);
  std::array<int, TetrisBoard::kMaxCols> heights{};
  board_.heights(heights.data());
  const auto orientations = orientationsOf(piece_);
  std::size_t i = 0;
  for (std::size_t o = 0; o < orientations.size(); ++o) {
    const int columns = config_.cols - orientations[o].width + 1;
    for (int c = 0; c < columns; ++c, ++i) {
      TetrisBoard after = board_;
      const DropOutcome outcome = after.drop(piece_, static_cast<int>(o), c, heights.data());
      out.placements[i] = {static_cast<int>(o), c, outcome.rowsRemoved, outcome.gameOver};
      after.features(config_.state, piece_, out.features.data() + i * dim);
    }
  }
}

}  // namespace gpfd::env

namespace gpfd::env {

AfterstateView Tetris::candidates() {
  if (gameOver_) return {};
  if (bulkAfterstates_) {
    afterstates(afterstates_);
  } else {
    afterstatesReference(afterstates_);
  }
  const std::size_t n = afterstates_.placements.size();
  rewards_.resize(n);
  ends_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    rewards_[i] = afterstates_.placements[i].rowsRemoved;
    ends_[i] = afterstates_.placements[i].gameOver ? 1 : 0;
  }
  return {n, afterstates_.features.data(), rewards_.data(), ends_.data()};
}

StepResult Tetris::play(std::size_t index) {
  const TetrisPlacement& p = afterstates_.placements.at(index);
  const double action[2] = {static_cast<double>(p.orientation), static_cast<double>(p.column)};
  return step(action);
}

std::vector<double> Tetris::knownValueWeights() const {
  if (config_.state != TetrisFeatures::Bertsekas) return {};
  std::vector<double> w(names_.size(), 0.0);
  w[static_cast<std::size_t>(2 * config_.cols - 1)] = -10.0;  // Max height.
  w[static_cast<std::size_t>(2 * config_.cols)] = -1.0;       // Holes.
  return w;
}

}  // namespace gpfd::env
