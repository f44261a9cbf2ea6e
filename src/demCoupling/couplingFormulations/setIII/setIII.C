#include "setIII.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace couplingFormulations
{
    defineTypeNameAndDebug(setIII, 0);
    addToRunTimeSelectionTable(couplingFormulation, setIII, dictionary);
}
}
