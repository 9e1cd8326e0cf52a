#include "cueplan/api/field_names.hpp"

namespace cueplan::api {

const std::initializer_list<FieldName> kCushionFlags = {
    {{"mass"}, "--mass"},
    {{"radius"}, "--radius"},
    {{"cushion_height"}, "--cushion-height"},
    {{"mu_cushion"}, "--mu-cushion"},
    {{"mu_table"}, "--mu-table"},
    {{"restitution"}, "--restitution"},
    {{"eta_squared"}, "--eta-squared"},
    {{"model"}, "--cushion-model"},
    {{"paper_steps"}, "--steps"},
    {{"tolerance"}, "--tolerance"},
    {{"table_fallback_tolerance"}, "--tolerance"},
};

std::string name_of(const physics::FieldPath& path, std::span<const FieldName> names) {
  const FieldName* best = nullptr;
  for (const FieldName& n : names)
    if (path.starts_with(n.field) && (best == nullptr || n.field.size() > best->field.size()))
      best = &n;
  return best != nullptr ? std::string(best->name) : path.text();
}

std::string message_in(const physics::ValidationError& error, std::span<const FieldName> names) {
  return error.message(name_of(error.field, names),
                       error.other ? name_of(*error.other, names) : std::string());
}

}  // namespace cueplan::api
