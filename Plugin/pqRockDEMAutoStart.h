/**
 * @class   pqRockDEMAutoStart
 * @brief   GUI start-up hook of the RockDEM plugin: draws DEM particles as spheres.
 *
 * The XML hint makes the particles' default representation Point Gaussian; this hook
 * completes it so that a particle is drawn as a sphere of its own radius: Sphere shader,
 * scaled by the Radius point array, no scale function, Gaussian radius 1. It applies to
 * output port 0 of every proxy whose XML name starts with "DEM" and whose data has a
 * Radius point array. Nothing else in the plugin needs the GUI.
 */
#ifndef pqRockDEMAutoStart_h
#define pqRockDEMAutoStart_h

#include <QObject>

class pqRepresentation;

class pqRockDEMAutoStart : public QObject
{
  Q_OBJECT
  typedef QObject Superclass;

public:
  pqRockDEMAutoStart(QObject* p = nullptr);
  ~pqRockDEMAutoStart() override;

  void startup();
  void shutdown();

private Q_SLOTS:
  void onRepresentationAdded(pqRepresentation* representation);

private:
  Q_DISABLE_COPY(pqRockDEMAutoStart)
};

#endif
