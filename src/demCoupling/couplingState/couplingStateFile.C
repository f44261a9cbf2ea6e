/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "couplingStateFile.H"
#include "error.H"
#include <fstream>

void Foam::writeCouplingStateFile(const fileName& file, const couplingState& s)
{
    std::ofstream os(file.c_str(), std::ios::binary);
    const char magic[8] = {'D', 'E', 'M', 'C', 'P', 'L', '2', '\0'};
    const int64_t n = s.Uprev.size();
    os.write(magic, sizeof magic);
    os.write(reinterpret_cast<const char*>(&n), sizeof n);
    const int64_t index = s.indexUprev;
    os.write(reinterpret_cast<const char*>(&index), sizeof index);
    os.write(reinterpret_cast<const char*>(s.G.cdata()), 3*sizeof(scalar));
    if (n)
    {
        os.write(reinterpret_cast<const char*>(s.Uprev.cdata()), 3*n*sizeof(scalar));
    }
    const int64_t nRamp = s.rampStart.size();
    os.write(reinterpret_cast<const char*>(&nRamp), sizeof nRamp);
    for (const auto& r : s.rampStart)
    {
        os.write(reinterpret_cast<const char*>(&r.first), sizeof r.first);
        os.write(reinterpret_cast<const char*>(&r.second), sizeof r.second);
    }
    if (!os.good())
    {
        FatalErrorInFunction
            << "cannot write " << file << exit(FatalError);
    }
}


void Foam::readCouplingStateFile(const fileName& file, couplingState& s)
{
    std::ifstream is(file.c_str(), std::ios::binary);
    char magic[8];
    int64_t n = -1;
    is.read(magic, sizeof magic);
    is.read(reinterpret_cast<char*>(&n), sizeof n);
    if (!is.good() || std::string(magic, 7) != "DEMCPL2" || n < 0)
    {
        FatalErrorInFunction
            << file << " is not a demFoam coupling state" << exit(FatalError);
    }
    int64_t index = -2;
    is.read(reinterpret_cast<char*>(&index), sizeof index);
    s.indexUprev = label(index);
    is.read(reinterpret_cast<char*>(s.G.data()), 3*sizeof(scalar));
    s.Uprev.setSize(label(n));
    if (n)
    {
        is.read(reinterpret_cast<char*>(s.Uprev.data()), 3*n*sizeof(scalar));
    }
    s.rampStart.clear();
    if (is.good() && is.peek() == std::ifstream::traits_type::eof())
    {
        is.clear();     // a file from before the ramps: none
    }
    else if (is.good())
    {
        int64_t nRamp = -1;
        is.read(reinterpret_cast<char*>(&nRamp), sizeof nRamp);
        for (int64_t k = 0; k < nRamp && is.good(); ++k)
        {
            int64_t id;
            scalar t0;
            is.read(reinterpret_cast<char*>(&id), sizeof id);
            is.read(reinterpret_cast<char*>(&t0), sizeof t0);
            s.rampStart[id] = t0;
        }
    }
    if (!is.good())
    {
        FatalErrorInFunction
            << file << " is truncated" << exit(FatalError);
    }
}
