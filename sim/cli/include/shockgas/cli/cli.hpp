// SPDX-License-Identifier: GPL-3.0-or-later
// Argument parsing with the messages every shockgas program gives: one line
// "<program>: error: <what>" and exit status 2 for any bad input, and for a
// misspelt option, config-file key or subcommand the nearest real one. Header-only, for
// the executables (the libraries do not depend on CLI11).
#pragma once

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/model/parameters.hpp"
#include "shockgas/cli/suggest.hpp"

namespace shockgas::cli {

// Exit status of every shockgas program for input a user can get wrong.
inline constexpr int bad_input = 2;

namespace detail {

inline void collect_names(const CLI::App& app, std::vector<std::string>& long_names,
                          std::vector<std::string>& short_names) {
    for (const CLI::Option* option : app.get_options()) {
        for (const auto& name : option->get_lnames()) long_names.push_back(name);
        for (const auto& name : option->get_snames()) short_names.push_back(name);
    }
    for (const CLI::App* sub : app.get_subcommands({})) collect_names(*sub, long_names, short_names);
}

// The first command-line word that looks like an option but is none, with the
// nearest real option: "unknown option '--restituion' (did you mean --restitution?)".
inline std::string unknown_option_message(const CLI::App& app, int argc, const char* const* argv) {
    std::vector<std::string> long_names, short_names;
    collect_names(app, long_names, short_names);
    for (int i = 1; i < argc; ++i) {
        const std::string word = argv[i];
        if (word == "--") break;
        if (word.rfind("--", 0) == 0) {
            const std::string name = word.substr(2, word.find('=') - 2);
            if (std::find(long_names.begin(), long_names.end(), name) != long_names.end()) continue;
            const std::string nearest = closest_name(name, long_names);
            return nearest.empty() ? fmt::format("unknown option '--{}' (see --help)", name)
                                   : fmt::format("unknown option '--{}' (did you mean --{}?)", name, nearest);
        }
        if (word.size() >= 2 && word[0] == '-' && std::isalpha(static_cast<unsigned char>(word[1])) &&
            std::find(short_names.begin(), short_names.end(), word.substr(1, 1)) == short_names.end())
            return fmt::format("unknown option '{}' (see --help)", word);
    }
    return "";
}

// A program with subcommands (shockgas-analyze, shockgas-dump) given none that it
// has: CLI11 says only "A subcommand is required", also for a misspelt one
// ("shockgas-analyze scalng run.h5"). The first word that is neither an option
// nor an option's value is the subcommand meant: "unknown subcommand 'scalng'
// (did you mean scaling?; the subcommands are decay, ...)". "" when a
// subcommand was parsed (the error is about its own arguments) or the program
// has none.
inline std::string unknown_subcommand_message(const CLI::App& app, int argc, const char* const* argv) {
    if (!app.get_subcommands().empty()) return "";  // the subcommands parsed
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
    if (names.empty()) return "";
    const std::string listed = fmt::format("the subcommands are {}", fmt::join(names, ", "));
    for (int i = 1; i < argc; ++i) {
        const std::string word = argv[i];
        if (word == "--") break;
        if (word.size() > 1 && word[0] == '-') {
            // An option of the program or of a subcommand (shockgas-dump's -o FILE, or -o given before the
            // subcommand's name): one that takes a value takes the next word too.
            const std::string name = word.substr(0, word.find('='));
            const CLI::Option* option = app.get_option_no_throw(name);
            for (const CLI::App* sub : app.get_subcommands({}))
                if (option == nullptr) option = sub->get_option_no_throw(name);
            if (option != nullptr && option->get_expected_min() > 0 && word.find('=') == std::string::npos) ++i;
            continue;
        }
        const std::string nearest = closest_name(word, names);
        return nearest.empty() ? fmt::format("unknown subcommand '{}' ({})", word, listed)
                               : fmt::format("unknown subcommand '{}' (did you mean {}?; {})", word, nearest, listed);
    }
    return fmt::format("a subcommand is required ({})", listed);
}

// CLI11's "INI was not able to parse KEY": an unknown key in the config file.
inline std::string unknown_key_message(const CLI::App& app, const std::string& cli11_message) {
    const std::string prefix = "INI was not able to parse ";
    if (cli11_message.rfind(prefix, 0) != 0) return "";
    const std::string key = cli11_message.substr(prefix.size());
    std::vector<std::string> long_names, short_names;
    collect_names(app, long_names, short_names);
    const CLI::Option* config = app.get_config_ptr();
    const std::string file = config != nullptr && config->count() > 0 ? config->as<std::string>() : "the config file";
    // CLI11 reads "[name]" as entering subcommand "name" ("name.++") and a
    // dotted key a.b as key b of section a; no program here has
    // configurable subcommands, so both are sections it does not have.
    const std::string opened = ".++";
    if (key.size() > opened.size() && key.compare(key.size() - opened.size(), opened.size(), opened) == 0)
        return fmt::format("section '[{}]' in {}: sections are not supported (write every option at the top level)",
                           key.substr(0, key.size() - opened.size()), file);
    if (key.find('.') != std::string::npos)
        return fmt::format("unknown option '{}' in {}: sections and dotted keys are not supported (write every "
                           "option at the top level)",
                           key, file);
    const std::string nearest = closest_name(key, long_names);
    return nearest.empty() ? fmt::format("unknown option '{}' in {}", key, file)
                           : fmt::format("unknown option '{}' in {} (did you mean {}?)", key, file, nearest);
}

}  // namespace detail

// Options that one option supplies itself (shockgas-burgers' --run brings N, L, the seed and the
// initial condition of the run): declared with CLI11's excludes, so that --help says so
// ("Excludes: --run"), and refused by parse in one line naming both values and why. CLI11's own
// message, "--run excludes --particles", says neither what was given nor why.
struct Exclusion {
    const CLI::Option* option;                // --run
    std::vector<const CLI::Option*> others;   // what it supplies
    std::string why;                          // "--run takes ... from the run (...)"
};
inline Exclusion exclude(CLI::Option* option, const std::vector<CLI::Option*>& others, std::string why) {
    Exclusion exclusion{option, {}, std::move(why)};
    for (CLI::Option* other : others) {
        option->excludes(other);  // both ways: each lists the other in --help
        exclusion.others.push_back(other);
    }
    return exclusion;
}

namespace detail {

// "--run 'a.h5' and --particles '2000' exclude each other: <why>; give one of them", for the first
// declared exclusion the command line breaks; "" for none (an excludes declared without exclude()).
inline std::string exclusion_message(const std::vector<Exclusion>& exclusions) {
    const auto given = [](const CLI::Option* option) {
        return fmt::format("{} '{}'", option->get_name(), fmt::join(option->results(), ","));
    };
    for (const Exclusion& exclusion : exclusions) {
        if (exclusion.option->count() == 0) continue;
        for (const CLI::Option* other : exclusion.others)
            if (other->count() > 0)
                return fmt::format("{} and {} exclude each other: {}; give one of them", given(exclusion.option),
                                   given(other), exclusion.why);
    }
    return "";
}

}  // namespace detail

// CLI::NonNegativeNumber lets "nan" through (nan < 0 is false), and a NaN
// interval would make every comparison with it false: progress lines never or
// always. Intervals must be finite numbers >= 0.
inline const CLI::Validator finite_non_negative(
    [](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(value) || value < 0.0)
            return fmt::format("must be a finite number >= 0, not '{}'", text);
        return "";
    },
    "NUMBER >= 0");

// Every program's --seed. A seed is checked as text: CLI11 reads any number beyond 2^64 - 1 as
// 2^64 - 1, so 2^64 and 10^23 both ran as that seed; and the file stores the
// seed as a signed 64-bit attribute (the type every reader of the schema
// knows, and that the archive's content hash covers), where a seed from 2^63
// on reads back negative in h5py and h5dump. Seeds are 0 .. 2^63 - 1.
inline const CLI::Validator seed_in_range(
    [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const char* const last = text.data() + text.size();
        const auto [end, error] = std::from_chars(text.data(), last, value);
        if (text.empty() || error != std::errc() || end != last ||
            value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
            return fmt::format("must be an integer from 0 to 2^63 - 1 = {}, not '{}'",
                               std::numeric_limits<std::int64_t>::max(), text);
        return "";
    },
    "0 .. 2^63-1");

// shockgas-sim's --realizations, checked as text with CLI11's own conversion
// (so every value it accepted still runs): a number that is no int, such as
// 1e12 or 3000000000, gave CLI11's bare "Could not convert". The realizations
// of a run are counted in an int; a larger ensemble runs as parts
// (--first-realization) joined by shockgas-merge.
inline const CLI::Validator realizations_in_range(
    [](std::string& text) -> std::string {
        int value = 0;
        if (CLI::detail::lexical_cast(text, value) && value >= 1) return "";
        char* end = nullptr;
        const double number = std::strtod(text.c_str(), &end);
        const bool too_many = end != text.c_str() && *end == '\0' && number > std::numeric_limits<int>::max();
        return fmt::format("must be an integer from 1 to 2^31 - 1 = {}, not '{}'{}", std::numeric_limits<int>::max(),
                           text,
                           too_many ? " (a larger ensemble runs as parts: --first-realization, then shockgas-merge)"
                                    : "");
    },
    "1 .. 2^31-1");

// A count written as an exact decimal, in scientific notation or with a
// fraction of zeros (-N 1e5, -R 2.5e3, --chains 4.0), is that whole number: its
// digits, computed from the text (no floating point, so 12345678901234567e2
// stays exact), for CLI11 to convert and range-check. A number with a
// fraction is refused as not a whole number, naming the text; plain integers
// and text that is no number pass unchanged, to the option's own checks.
inline std::string whole_number_digits(const std::string& text, std::string& error) {
    error.clear();
    std::size_t i = 0;
    std::string sign;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) sign = text[i++] == '-' ? "-" : "";
    std::string digits;
    std::size_t after_point = 0;
    bool plain = true;  // digits only, no point and no exponent
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) != 0) digits += text[i++];
    if (i < text.size() && text[i] == '.') {
        ++i;
        plain = false;
        while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) != 0) {
            digits += text[i++];
            ++after_point;
        }
    }
    long long exponent = 0;
    bool exponent_ok = true;
    if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        plain = false;
        const char* first = text.data() + i;
        if (i < text.size() && text[i] == '+') ++first;
        const auto [end, code] = std::from_chars(first, text.data() + text.size(), exponent);
        exponent_ok = code == std::errc() && end == text.data() + text.size() && end != first;
        i = text.size();
    }
    const auto refuse = [&](const char* why) {
        error = fmt::format("must be a whole number{}, not '{}'", why, text);
        return text;
    };
    if (digits.empty() || i != text.size() || !exponent_ok) return text;  // no number: the option's checks say so
    if (plain) return text;  // a plain integer: CLI11's to convert
    // value = digits x 10^shift
    const long long shift = exponent - static_cast<long long>(after_point);
    constexpr long long most_digits = 30;  // beyond every count's range; CLI11 then says "too large"
    if (shift < 0) {
        const auto cut = static_cast<std::size_t>(std::min<long long>(-shift, static_cast<long long>(digits.size())));
        if (digits.find_first_not_of('0', digits.size() - cut) != std::string::npos) return refuse("");
        digits.resize(digits.size() - cut);
        if (digits.empty()) digits = "0";
    } else {
        if (shift > most_digits) return refuse(" in range");
        digits.append(static_cast<std::size_t>(shift), '0');
    }
    const std::size_t lead = std::min(digits.find_first_not_of('0'), digits.size() - 1);
    return sign + digits.substr(lead);
}

inline const CLI::Validator whole_number(
    [](std::string& text) -> std::string {
        std::string error;
        text = whole_number_digits(text, error);
        return error;
    },
    "", "whole_number");

// Gives every integer option of app and its subcommands (CLI11's type names
// INT and UINT) the whole_number rewriting, before its own checks.
inline void accept_whole_numbers(CLI::App& app) {
    for (CLI::Option* option : app.get_options()) {
        const std::string type = option->get_type_name();
        if (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0) option->transform(whole_number);
    }
    for (CLI::App* sub : app.get_subcommands({})) accept_whole_numbers(*sub);
}

// Parses; returns -1 to go on, or the exit status: 0 after --help or
// --version, bad_input after a parse error (printed as one line). exclusions:
// the program's exclude() declarations, whose breach is named with its reason.
inline int parse(CLI::App& app, int argc, char** argv, const std::string& program,
                 const std::vector<Exclusion>& exclusions = {}) {
    accept_whole_numbers(app);
    try {
        app.parse(argc, argv);
        return -1;
    } catch (const CLI::Success& done) {
        return app.exit(done);
    } catch (const CLI::ParseError& error) {
        std::string message;
        if (dynamic_cast<const CLI::ExtrasError*>(&error) != nullptr)
            message = detail::unknown_option_message(app, argc, argv);
        else if (dynamic_cast<const CLI::ConfigError*>(&error) != nullptr)
            message = detail::unknown_key_message(app, error.what());
        else if (dynamic_cast<const CLI::ExcludesError*>(&error) != nullptr)
            message = detail::exclusion_message(exclusions);
        // A misspelt or missing subcommand: CLI11's RequiredError ("A subcommand is required"), or an
        // ExtrasError whose words are all real options.
        if (message.empty() && (dynamic_cast<const CLI::RequiredError*>(&error) != nullptr ||
                                dynamic_cast<const CLI::ExtrasError*>(&error) != nullptr))
            message = detail::unknown_subcommand_message(app, argc, argv);
        if (message.empty()) message = error.what();
        // CLI11's messages can span lines; the house form is one line.
        for (char& c : message)
            if (c == '\n' || c == '\r') c = ' ';
        fmt::print(stderr, "{}: error: {}\n", program, message);
        return bad_input;
    }
}

// Runs a program's work (a callable returning its exit status) and gives what
// it throws the house form. Input a user can get wrong, InputError, or an HDF5
// error (which names the file), prints "<program>: error: <what>" and returns
// bad_input; anything else is the program's own defect, printed as
// "<program>: internal error: <what>" with status 1, so that a bug never passes
// for bad input. A program that knows another exception to be the user's turns
// it into an InputError inside `work` (shockgas-analyze's InsufficientData).
template <class Work>
int run(const std::string& program, Work&& work) {
    try {
        return work();
    } catch (const InputError& error) {
        fmt::print(stderr, "{}: error: {}\n", program, error.what());
        return bad_input;
    } catch (const h5::Error& error) {
        fmt::print(stderr, "{}: error: {}\n", program, error.what());
        return bad_input;
    } catch (const std::exception& error) {
        fmt::print(stderr, "{}: internal error: {}\n", program, error.what());
        return 1;
    }
}

}  // namespace shockgas::cli
