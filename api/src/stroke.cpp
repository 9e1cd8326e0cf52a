#include "cueplan/api/stroke.hpp"

#include "cueplan/api/field_names.hpp"
#include "cueplan/problems/stroke_ranges.hpp"

namespace cueplan::api {
namespace {

namespace phys = cueplan::physics;

}  // namespace

std::string check_shot_inputs(const phys::Shot& shot, const ShotNames& names) {
  const phys::Validation e = shot.validate();
  if (!e)
    return problems::check_stroke_ranges(
               shot, {names.speed, names.aim, names.topspin, names.sidespin, nullptr})
        .error;
  const FieldName by_field[] = {{{"speed"}, names.speed},
                                {{"aim_deg"}, names.aim},
                                {{"topspin_k"}, names.topspin},
                                {{"sidespin_k"}, names.sidespin},
                                {{"elevation_deg"}, names.elevation}};
  return message_in(*e, by_field);
}

std::vector<std::string> shot_warnings(const phys::Shot& shot, const ShotNames& names) {
  return problems::check_stroke_ranges(
             shot, {names.speed, names.aim, names.topspin, names.sidespin, nullptr})
      .warnings;
}

}  // namespace cueplan::api
