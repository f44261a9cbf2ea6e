/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "keyChecker.H"
#include "OStringStream.H"
#include <cctype>
#include <cmath>

using namespace Foam;

namespace
{
    using kind = keySpec::kind;
    const double inf = HUGE_VAL;

    //- Edit distance (insert, delete, substitute, swap of neighbours), case-blind
    label editDistance(const std::string& a, const std::string& b)
    {
        const label n = a.size(), m = b.size();
        List<labelList> d(n + 1, labelList(m + 1, 0));
        for (label i = 0; i <= n; ++i) d[i][0] = i;
        for (label j = 0; j <= m; ++j) d[0][j] = j;
        for (label i = 1; i <= n; ++i)
        {
            for (label j = 1; j <= m; ++j)
            {
                const bool same = std::tolower(a[i-1]) == std::tolower(b[j-1]);
                d[i][j] = min(min(d[i-1][j] + 1, d[i][j-1] + 1), d[i-1][j-1] + !same);
                if
                (
                    i > 1 && j > 1
                 && std::tolower(a[i-1]) == std::tolower(b[j-2])
                 && std::tolower(a[i-2]) == std::tolower(b[j-1])
                )
                {
                    d[i][j] = min(d[i][j], d[i-2][j-2] + 1);
                }
            }
        }
        return d[n][m];
    }


    //- " (did you mean X?)" for the closest candidate within reach, else ""
    std::string suggestion(const word& w, const wordList& candidates)
    {
        label best = labelMax;
        word bestName;
        for (const word& c : candidates)
        {
            const label dist = editDistance(w, c);
            if (dist < best)
            {
                best = dist;
                bestName = c;
            }
        }
        const label reach = max(label(2), label(w.size()/3));
        if (best <= reach)
        {
            return " (did you mean " + bestName + "?)";
        }
        return "";
    }


    std::string rangeText(const keySpec& k)
    {
        OStringStream os;
        const bool hasLo = k.lo > -inf, hasHi = k.hi < inf;
        if (hasLo) os << k.lo << (k.loOpen ? " < " : " <= ");
        os << k.name;
        if (hasHi) os << (k.hiOpen ? " < " : " <= ") << k.hi;
        return os.str();
    }


    bool inRange(const keySpec& k, const scalar v)
    {
        if (!std::isfinite(v)) return false;
        if (k.loOpen ? !(v > k.lo) : !(v >= k.lo)) return false;
        if (k.hiOpen ? !(v < k.hi) : !(v <= k.hi)) return false;
        return true;
    }
}


// * * * * * * * * * * * * * * * * Text * * * * * * * * * * * * * * * * * //

std::string Foam::keyChecker::numText(const scalar x)
{
    OStringStream os;
    os << x;
    return os.str();
}


std::string Foam::keyChecker::listText(const wordList& names)
{
    std::string s;
    forAll(names, i)
    {
        s += (i ? ", " : "") + names[i];
    }
    return s;
}


std::string Foam::keyChecker::valueText(const entry& e)
{
    if (e.isDict()) return "{ ... }";
    OStringStream os;
    const ITstream& is = e.stream();
    forAll(is, i)
    {
        os << (i ? " " : "") << is[i];
    }
    return os.str();
}


// * * * * * * * * * * * * * * * * Checks  * * * * * * * * * * * * * * * * //

void Foam::keyChecker::fail
(
    const dictionary& d,
    const word& scope,
    const std::string& key,
    const std::string& value,
    const std::string& what
) const
{
    FatalIOErrorInFunction(d)
        << file_.c_str() << ": keyword " << scope.c_str() << key.c_str();
    if (!value.empty())
    {
        FatalIOError << " value " << value.c_str();
    }
    FatalIOError << ": " << what.c_str() << exit(FatalIOError);
    ::abort();
}


// Unknown keywords, types, ranges and choices of one scope
void Foam::keyChecker::check
(
    const dictionary& d,
    const word& scope,
    const List<keySpec>& specs
) const
{
    wordList names(specs.size());
    forAll(specs, i) names[i] = specs[i].name;

    for (const entry& e : d)
    {
        const word& key = e.keyword();
        // user variables for $macros: a leading underscore
        if (key.empty() || key[0] == '_' || key == "FoamFile") continue;
        const label i = names.find(key);
        if (i < 0)
        {
            fail
            (
                d, scope, key, valueText(e),
                "unknown keyword" + suggestion(key, names)
              + ". Allowed in " + (scope.empty() ? word("the top level") : scope)
              + ": " + listText(names)
              + " (names starting with _ are free for $variables)"
            );
        }
        checkValue(d, scope, e, specs[i]);
    }
}

void Foam::keyChecker::checkValue
(
    const dictionary& d,
    const word& scope,
    const entry& e,
    const keySpec& k
) const
{
    const std::string v(valueText(e));
    if (k.type == kind::Dict || (k.type == kind::Distribution && e.isDict()))
    {
        if (!e.isDict())
        {
            fail(d, scope, k.name, v, "expected a dictionary { ... }");
        }
        return;
    }
    if (e.isDict())
    {
        fail(d, scope, k.name, v, "expected a value, not a dictionary");
    }
    const ITstream& is = e.stream();
    switch (k.type)
    {
        case kind::Scalar:
        case kind::Distribution:
        case kind::Label:
        {
            const bool isLabel = k.type == kind::Label;
            if
            (
                is.size() != 1
             || !(isLabel ? is[0].isLabel() : is[0].isNumber())
            )
            {
                fail
                (
                    d, scope, k.name, v,
                    isLabel ? "expected an integer" : "expected a number"
                );
            }
            const scalar x = isLabel ? scalar(is[0].labelToken()) : is[0].number();
            if (!inRange(k, x))
            {
                fail(d, scope, k.name, v, "out of range; allowed " + rangeText(k));
            }
            break;
        }
        case kind::Word:
        {
            if (is.size() != 1 || !is[0].isWord())
            {
                fail(d, scope, k.name, v, "expected a single word");
            }
            const word w(is[0].wordToken());
            if (k.words.size() && !k.words.found(w))
            {
                fail
                (
                    d, scope, k.name, v,
                    "not known" + suggestion(w, k.words)
                  + ". Allowed: " + listText(k.words)
                );
            }
            break;
        }
        case kind::Bool:
        {
            static const wordList yesNo
            ({"true", "false", "yes", "no", "on", "off"});
            if (is.size() != 1 || !is[0].isWord() || !yesNo.found(is[0].wordToken()))
            {
                fail(d, scope, k.name, v, "allowed " + listText(yesNo));
            }
            break;
        }
        case kind::Vector:
        {
            bool ok = is.size() == 5 && is[0].isPunctuation()
                && is[0].pToken() == token::BEGIN_LIST
                && is[4].isPunctuation() && is[4].pToken() == token::END_LIST;
            for (label j = 1; ok && j <= 3; ++j)
            {
                ok = is[j].isNumber() && std::isfinite(is[j].number());
            }
            if (!ok)
            {
                fail(d, scope, k.name, v, "expected a vector (x y z) of finite numbers");
            }
            break;
        }
        case kind::List:
        {
            const bool ok = is.size() >= 2
             && (
                    (is[0].isPunctuation() && is[0].pToken() == token::BEGIN_LIST)
                 || (is[0].isLabel() && is.size() >= 3)
                );
            if (!ok)
            {
                fail(d, scope, k.name, v, "expected a list ( ... )");
            }
            break;
        }
        default:
            break;
    }
}


// Required keyword
void Foam::keyChecker::require
(
    const dictionary& d,
    const word& scope,
    const word& key,
    const std::string& what
) const
{
    if (!d.found(key, keyType::LITERAL))
    {
        fail(d, scope, key, "", "missing; required: " + what);
    }
}


// A name that must be one of the given ones (materials, patches)
void Foam::keyChecker::checkName
(
    const dictionary& d,
    const word& scope,
    const word& key,
    const word& value,
    const wordList& valid,
    const std::string& what
) const
{
    if (!valid.found(value))
    {
        fail
        (
            d, scope, key, value,
            "no such " + what + suggestion(value, valid)
          + ". Allowed: " + listText(valid)
        );
    }
}


// ************************************************************************* //
