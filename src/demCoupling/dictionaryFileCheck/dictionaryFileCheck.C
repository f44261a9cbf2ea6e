/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "dictionaryFileCheck.H"
#include "IOdictionary.H"
#include "IStringStream.H"
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

namespace
{

// The numbers on one line of text that do not fit a double (strtod gives
// +-inf with ERANGE), with the keyword that starts the line
bool outOfRange
(
    const std::string& line,
    std::string& keyword,
    std::string& value
)
{
    static const std::regex number
    (
        R"([-+]?(\d+\.?\d*|\.\d+)[eE][-+]?\d+)"
    );
    for
    (
        std::sregex_iterator it(line.begin(), line.end(), number), end;
        it != end;
        ++it
    )
    {
        const std::string v(it->str());
        errno = 0;
        const double d = std::strtod(v.c_str(), nullptr);
        if (errno == ERANGE && std::isinf(d))
        {
            std::istringstream words(line);
            words >> keyword;
            value = v;
            return true;
        }
    }
    return false;
}

} // End anonymous namespace


bool Foam::dictionaryFileCheck(const IOobject& io)
{
    const fileName file(typeFilePath<IOdictionary>(io));
    if (file.empty() || !isFile(file))
    {
        return true;  // the normal read reports the missing file
    }
    std::ifstream in(file);
    std::stringstream buf;
    buf << in.rdbuf();
    const std::string text(buf.str());
    const fileName shown(io.instance()/io.name());

    // numbers out of range, line by line
    {
        std::istringstream lines(text);
        std::string line, keyword, value;
        for (label n = 1; std::getline(lines, line); ++n)
        {
            line = line.substr(0, line.find("//"));
            if (outOfRange(line, keyword, value))
            {
                FatalErrorInFunction
                    << shown.c_str() << " line " << n << ": keyword "
                    << keyword.c_str() << " value " << value.c_str()
                    << ": the number is out of range (double precision "
                    << "holds magnitudes up to about 1.8e308); allowed: a "
                    << "finite number" << nl << "file: " << file
                    << exit(FatalError);
            }
        }
    }

    // duplicate keywords: the same text read with duplicates an error
    // (on the first line, so that line numbers stay those of the file)
    IStringStream is("#inputMode error " + text);
    is.name() = file;
    const bool throwing = FatalIOError.throwExceptions();
    std::string duplicate;
    label line = -1;
    try
    {
        dictionary d(is);
    }
    catch (const Foam::IOerror& e)
    {
        const std::string msg(e.message());
        const std::string::size_type at = msg.find("duplicate entry: ");
        if (at != std::string::npos)
        {
            duplicate = msg.substr(at + 17);
            duplicate = duplicate.substr(0, duplicate.find_first_of(" \n\""));
            line = e.ioStartLineNumber();
        }
    }
    catch (const Foam::error&)
    {
        // other read errors: reported by the normal read
    }
    FatalIOError.throwExceptions(throwing);
    if (!duplicate.empty())
    {
        // the lines that start with the keyword (both places, usually)
        std::string where;
        {
            std::string quoted;
            for (const char c : duplicate)
            {
                if (!std::isalnum(static_cast<unsigned char>(c))) quoted += '\\';
                quoted += c;
            }
            const std::regex starts("^\\s*" + quoted + "(\\s|$)");
            std::istringstream lines(text);
            std::string l;
            label nFound = 0;
            for (label n = 1; std::getline(lines, l); ++n)
            {
                if (std::regex_search(l, starts))
                {
                    where += (nFound++ ? " and " : "") + std::to_string(n);
                }
            }
            where = (nFound > 1 ? "lines " : "line ")
              + (nFound > 1 ? where : std::to_string(line));
        }
        FatalErrorInFunction
            << shown.c_str() << " " << where.c_str() << ": keyword "
            << duplicate.c_str() << " is given a second time in the same "
            << "dictionary (OpenFOAM would keep the last value without a "
            << "word); allowed: each keyword once (to override an #included "
            << "entry on purpose, put #inputMode overwrite before it)" << nl
            << "file: " << file << exit(FatalError);
    }
    return true;
}


// ************************************************************************* //
