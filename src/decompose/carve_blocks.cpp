// SPDX-License-Identifier: GPL-3.0-or-later
// Carving (thesis Section 4.3.3), the entry point: carves every box's region
// in parallel (carve_box_region.h), then moves box faces off the contacts
// no axis-aligned cut separated (contact_mover.h) and carves the changed
// regions again; see carve_blocks.h for the outline.
#include "subfab/decompose/carve_blocks.h"

#include <atomic>
#include <string>
#include <utility>
#include <vector>

#include "decompose/carve_box_region.h"
#include "decompose/contact_mover.h"
#include "geometry/solid_index.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/geometry/axis.h"
#include "subfab/validate/validate_decomposition.h"

namespace subfab {
namespace {
using detail::BoxFace;
using detail::BoxPieces;
using detail::carve_box_region;
using detail::Contact;
using detail::ContactMover;
}  // namespace

CarveResult carve_blocks(const Mesh& solid, const std::vector<HeightBox>& ordered_boxes,
                         const CarveOptions& options) {
  Progress* progress = options.progress;
  if (!(options.contact_move > 0) || options.max_contact_rounds < 0)
    throw InvalidArgumentError("carve_blocks: contact_move must be positive and max_contact_rounds >= 0");
  const detail::SolidIndex index(solid, overhang_sine(options.max_overhang_deg), options.allowed_overhangs,
                                 options.overhang_floors);
  HeightFieldOptions height_field;
  height_field.normal_tolerance = height_field_normal_tolerance(options.max_overhang_deg);
  if (options.allowed_overhangs) {  // the allowed faces may lean as far as they do (their undercuts are measured later)
    if (options.allowed_overhangs->size() != solid.num_faces())
      throw InvalidArgumentError("carve_blocks: one overhang allowance per face expected");
    for (std::size_t f = 0; f < solid.num_faces(); ++f) {
      const std::uint8_t bits = (*options.allowed_overhangs)[f];
      if (!bits) continue;
      const Vec3 n = face_unit_normal(solid, f);
      for (int k = 0; k < 3; ++k)
        if (bits & (1u << k)) height_field.normal_tolerance = std::max(height_field.normal_tolerance, std::abs(n[k]) + 1e-3);
    }
  }
  std::vector<HeightBox> boxes = ordered_boxes;
  std::vector<BoxPieces> per_box(boxes.size());
  std::atomic<std::size_t> done{0};
  parallel_for(0, boxes.size(), [&](std::size_t i) {
    per_box[i] = carve_box_region(solid, index, boxes, i);
    if (progress) progress->update(++done, boxes.size());
  });

  // Contacts no axis-aligned cut separated: move one region face holding
  // the contact off it, then carve again the boxes whose regions changed.
  // A move also changes the regions of later boxes (a moved hole face): it
  // is kept only when every piece of every box carved again is still a
  // height field along its box's axis (a later box whose base lay in the
  // moved plane would get faces one step above its base: anchor.off), and
  // taken back otherwise.
  ContactMover mover(index, boxes, options, bounding_box(solid).diagonal());
  auto all_height_fields = [&](const std::vector<std::size_t>& ids, const std::vector<BoxPieces>& pieces) {
    for (std::size_t n = 0; n < ids.size(); ++n)
      for (const Mesh& m : pieces[n].pieces)
        if (!is_height_field(m, axis_direction(boxes[ids[n]].axis), height_field)) return false;
    return true;
  };
  for (int round = 0; round < options.max_contact_rounds; ++round) {
    bool moved_any = false;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const std::vector<Contact> contacts = per_box[i].contacts;
      bool recarved_i = false;
      for (const Contact& c : contacts) {
        if (recarved_i) break;  // a move this round already changed the region
        for (const BoxFace& f : c.faces) {
          // Outward, then inward, at growing steps, until a move is kept.
          const HeightBox before = boxes[f.box];
          bool kept = false;
          while (!kept && mover.can_try(f)) {
            for (const Box3& moved : mover.candidates(f)) {
              std::vector<char> dirty(boxes.size(), 0);
              mover.apply(f, moved, dirty);
              std::vector<std::size_t> again;
              for (std::size_t j = 0; j < boxes.size(); ++j)
                if (dirty[j]) again.push_back(j);
              std::vector<BoxPieces> redone(again.size());
              parallel_for(0, again.size(),
                           [&](std::size_t n) { redone[n] = carve_box_region(solid, index, boxes, again[n]); });
              if (!all_height_fields(again, redone)) {
                mover.undo(f, before);
                continue;
              }
              for (std::size_t n = 0; n < again.size(); ++n) {
                per_box[again[n]] = std::move(redone[n]);
                recarved_i = recarved_i || again[n] == i;
              }
              kept = true;
              break;
            }
          }
          if (!kept) continue;
          moved_any = true;
          break;
        }
      }
    }
    if (!moved_any) break;
  }

  CarveResult result;
  result.num_moved_faces = mover.num_moves();
  for (std::size_t i = 0; i < per_box.size(); ++i) {
    BoxPieces& p = per_box[i];
    result.num_dropped_pieces += p.num_dropped;
    result.num_split_regions += p.split_region ? 1 : 0;
    result.num_pinched_regions += p.num_pinch_cuts > 0 ? 1 : 0;
    result.num_pinch_cuts += p.num_pinch_cuts;
    result.num_unresolved_pinches += p.num_unresolved_pinches;
    result.num_degenerate_faces += p.rounding.num_degenerate_faces;
    result.num_flipped_faces += p.rounding.num_flipped_faces;
    for (Mesh& m : p.pieces)
      result.blocks.push_back(Block{std::move(m), boxes[i].axis, static_cast<int>(i)});
  }
  if (progress) {
    progress->info(std::to_string(result.blocks.size()) + " blocks carved from " +
                   std::to_string(ordered_boxes.size()) + " boxes (" + std::to_string(result.num_dropped_pieces) +
                   " interior pieces dropped)");
    if (result.num_split_regions > 0)
      progress->warn(std::to_string(result.num_split_regions) +
                     " box regions were not manifold and were cut into disjoint boxes");
    if (result.num_pinched_regions > 0)
      progress->info(std::to_string(result.num_pinched_regions) +
                     " box regions touched by the surface from inside were cut through the contact (" +
                     std::to_string(result.num_pinch_cuts) + " planes)");
    if (result.num_moved_faces > 0)
      progress->info(std::to_string(result.num_moved_faces) +
                     " box faces moved off contacts no axis-aligned cut could separate");
    if (result.num_unresolved_pinches > 0)
      progress->warn(std::to_string(result.num_unresolved_pinches) +
                     " points where the surface touches a box region from inside could not be cut apart: the "
                     "blocks there touch themselves");
    if (result.num_degenerate_faces + result.num_flipped_faces > 0)
      progress->warn("rounding the exact blocks to doubles made " + std::to_string(result.num_degenerate_faces) +
                     " faces degenerate and flipped " + std::to_string(result.num_flipped_faces));
  }
  return result;
}

}  // namespace subfab
