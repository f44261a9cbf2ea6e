/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "keySpec.H"

namespace
{

//- <type>Coeffs -> the model's coeffKeys(); filled while the library loads
Foam::HashTable<Foam::keySpec::keysFunction>& coeffTable()
{
    static Foam::HashTable<Foam::keySpec::keysFunction> table;
    return table;
}

}


Foam::keySpec::addCoeffs::addCoeffs(const char* dictName, keysFunction f)
{
    coeffTable().set(dictName, f);
}


Foam::List<Foam::keySpec> Foam::keySpec::coeffKeysOf(const word& dictName)
{
    const auto iter = coeffTable().cfind(dictName);
    return iter.found() ? (*iter)() : List<keySpec>();
}
