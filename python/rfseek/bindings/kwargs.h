/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * Keyword construction for the bound parameter structs: T(**fields), each key one of
 * T::keys(), set through the struct's Python attributes (so types convert as usual).
 */

#ifndef INCLUDED_RFSEEK_BINDINGS_KWARGS_H
#define INCLUDED_RFSEEK_BINDINGS_KWARGS_H

#include <pybind11/pybind11.h>
#include <algorithm>
#include <string>

template <typename T>
T rfseek_from_kwargs(const pybind11::kwargs& kw, const char* type_name)
{
    namespace py = pybind11;
    T value;
    py::object self = py::cast(&value, py::return_value_policy::reference);
    const auto keys = T::keys();
    for (const auto& item : kw) {
        const auto key = py::cast<std::string>(item.first);
        if (std::find(keys.begin(), keys.end(), key) == keys.end() ||
            !py::hasattr(self, key.c_str()))
            throw py::type_error(std::string(type_name) +
                                 "() got an unexpected keyword argument '" + key + "'");
        try {
            py::setattr(self, key.c_str(), item.second);
        } catch (py::error_already_set& e) {
            if (!e.matches(PyExc_TypeError))
                throw;
            // A wrong type is a bad value like any other: ValueError naming the field.
            const py::object current = py::getattr(self, key.c_str());
            const std::string type =
                current.is_none()
                    ? "NoneType"
                    : py::cast<std::string>(current.get_type().attr("__name__"));
            std::string expected = type == "int"     ? "an integer (counts, lengths and "
                                                       "seeds: >= 0)"
                                   : type == "float" ? "a number"
                                   : type == "bool"  ? "True or False"
                                   : type == "str"   ? "a string"
                                                     : "a number or None";
            if (!current.is_none())
                expected += ", default " + py::cast<std::string>(py::repr(current));
            throw py::value_error(std::string(type_name) + "." + key + " = " +
                                  py::cast<std::string>(py::repr(item.second)) +
                                  ": must be " + expected);
        }
    }
    return value;
}

#endif /* INCLUDED_RFSEEK_BINDINGS_KWARGS_H */
