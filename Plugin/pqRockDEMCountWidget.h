/**
 * @class   pqRockDEMCountWidget
 * @brief   Properties-panel widget of an editable 64-bit count (panel_widget="rockdem_count").
 *
 * ParaView 5.11's Properties panel makes no widget for an IdType property, so a 64-bit count
 * (Initial Elements: a count too large for 32 bits must reach the engine, which says how much
 * memory it needs, instead of overflowing in the property) would not appear in the GUI at
 * all. This widget edits one: a line edit that takes whole numbers (a sign and up to 18
 * digits), marks the panel modified as the user types, and sets the property on Apply; the
 * engine's validation names the property, the value and the valid range for a bad count.
 * The line edit is named "LineEdit0", as ParaView names its integer widgets, e.g.
 * `.../ProxyPanel/InitialElements/LineEdit0`, for ParaView's recorded GUI tests.
 */
#ifndef pqRockDEMCountWidget_h
#define pqRockDEMCountWidget_h

#include "pqPropertyWidget.h"

class pqLineEdit;

class pqRockDEMCountWidget : public pqPropertyWidget
{
  Q_OBJECT
  typedef pqPropertyWidget Superclass;

public:
  pqRockDEMCountWidget(vtkSMProxy* proxy, vtkSMProperty* property, QWidget* parent = nullptr);
  ~pqRockDEMCountWidget() override;

  /// Sets the property to the count typed (Apply).
  void apply() override;
  /// Shows the property's value again (Reset).
  void reset() override;

private Q_SLOTS:
  void showValue();

private:
  Q_DISABLE_COPY(pqRockDEMCountWidget)
  pqLineEdit* Edit;
};

#endif
