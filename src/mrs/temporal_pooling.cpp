#include "mrs_vpr/mrs/temporal_pooling.hpp"

#include <algorithm>

namespace mrs_vpr {

PooledReference::PooledReference(SequenceView reference, int stride, const CompactCells& compact)
    : reference_(reference), kept_(stride > 1 ? reference.coarseCells(stride, compact.geometry()) : SequenceView{}),
      stride_(stride), compact_(compact) {}

const std::uint8_t* PooledReference::cell(int grid_index) {
  if (stride_ == 1) return reference_.frame(grid_index);
  if (grid_index < kept_.count) return kept_.frame(grid_index);
  if (known_.empty()) {
    known_.assign(static_cast<std::size_t>(size()), 0);
    cells_.resize(known_.size() * static_cast<std::size_t>(cellSize()));
  }
  std::uint8_t* cell = cells_.data() + static_cast<std::ptrdiff_t>(grid_index) * cellSize();
  if (!known_[static_cast<std::size_t>(grid_index)]) {
    compact_.cell(reference_, grid_index * stride_, stride_, cell);
    known_[static_cast<std::size_t>(grid_index)] = 1;
  }
  return cell;
}

PooledReference::Run PooledReference::run(int first, int wanted) {
  if (stride_ == 1) return {reference_.frame(first), reference_.pitch(), wanted};
  if (first < kept_.count) return {kept_.frame(first), kept_.pitch(), std::min(wanted, kept_.count - first)};
  for (int index = first; index < first + wanted; ++index) cell(index);  // Computes the missing ones.
  return {cells_.data() + static_cast<std::ptrdiff_t>(first) * cellSize(), cellSize(), wanted};
}

}  // namespace mrs_vpr
