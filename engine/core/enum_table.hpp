#pragma once
// One table per enum: every value with its user-facing name, in the order --help, the viewer panel
// and the sweeps list them. The name, the parser and the list of values all read the table, so
// they cannot disagree; tests/unit/test_enum_tables.cpp checks every table is complete and unique.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lp {

template <typename E>
struct EnumName {
    E value;
    const char* name;
};

// The value's name; "?" only for a value the table lacks (the tests make that impossible).
template <typename E, std::size_t N>
constexpr const char* enumName(const EnumName<E> (&table)[N], E value) {
    for (const EnumName<E>& e : table)
        if (e.value == value) return e.name;
    return "?";
}

template <typename E, std::size_t N>
std::optional<E> parseEnum(const EnumName<E> (&table)[N], std::string_view name) {
    for (const EnumName<E>& e : table)
        if (name == e.name) return e.value;
    return std::nullopt;
}

template <typename E, std::size_t N>
std::vector<E> enumValues(const EnumName<E> (&table)[N]) {
    std::vector<E> values;
    for (const EnumName<E>& e : table) values.push_back(e.value);
    return values;
}

// "a, b, c": for error messages listing what is accepted.
template <typename E, std::size_t N>
std::string enumNameList(const EnumName<E> (&table)[N]) {
    std::string list;
    for (const EnumName<E>& e : table) list += (list.empty() ? "" : ", ") + std::string(e.name);
    return list;
}

}  // namespace lp
